// Standalone driver of a fuzz target (LLVMFuzzerTestOneInput) for the normal build, where
// libFuzzer is not available: what `ctest -L fuzz` runs. It
//   1. replays every file under the given paths (the seed corpus: the shipped scenes and
//      studies, tests/fuzz/corpus/; and tests/fuzz/regressions/, every crash ever found), then
//   2. feeds N deterministic mutants of those files (tests/fuzz/json_mutator.hpp; fixed seed,
//      so a failure reproduces exactly) to the target.
// The target aborts on a bug; the driver then writes the input that did it to
// `<program>-crash.json` in the working directory (with a line on stderr naming the input), so it
// can be added to tests/fuzz/regressions/ once fixed. The long, coverage-guided campaign is
// ci/fuzz.sh (libFuzzer, clang, sanitizers); docs/vv/robustness.md.
//
// Usage: PROGRAM [--mutants N] [--seed S] PATH...   (PATH: a file, or a directory read recursively)
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_target.hpp"
#include "json_mutator.hpp"

namespace {

namespace fs = std::filesystem;

// What the crash handler needs, prepared before each input (it may only call write/open/raise).
const std::string* g_input = nullptr;
char g_input_name[512] = "";
char g_crash_file[512] = "";

void write_all(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = write(fd, p, n);
    if (w <= 0) return;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
}

void write_str(int fd, const char* s) { write_all(fd, s, std::strlen(s)); }

extern "C" void on_crash(int sig) {
  write_str(2, "lsi fuzz driver: signal ");
  write_str(2, sig == SIGABRT   ? "SIGABRT"
               : sig == SIGSEGV ? "SIGSEGV"
               : sig == SIGBUS  ? "SIGBUS"
               : sig == SIGFPE  ? "SIGFPE"
                                : "SIGILL");
  write_str(2, " on input ");
  write_str(2, g_input_name);
  if (g_input) {
    const int fd = open(g_crash_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      write_all(fd, g_input->data(), g_input->size());
      close(fd);
      write_str(2, "; the input is in ");
      write_str(2, g_crash_file);
    }
  }
  write_str(2, "\n");
  signal(sig, SIG_DFL);
  raise(sig);
}

void install_crash_handler(const std::string& crash_file) {
  std::snprintf(g_crash_file, sizeof g_crash_file, "%s", crash_file.c_str());
  // An alternate stack, so that a stack overflow (deep recursion) is reported too.
  static std::vector<char> alt_stack(1 << 16);
  stack_t ss{};
  ss.ss_sp = alt_stack.data();
  ss.ss_size = alt_stack.size();
  sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_handler = on_crash;
  sa.sa_flags = SA_ONSTACK;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) sigaction(sig, &sa, nullptr);
}

void run_one(const std::string& input, const std::string& name) {
  g_input = &input;
  std::snprintf(g_input_name, sizeof g_input_name, "%s", name.c_str());
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  g_input = nullptr;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

[[noreturn]] void usage_error(const std::string& what) {
  std::fprintf(stderr, "fuzz driver: %s\nusage: PROGRAM [--mutants N] [--seed S] PATH...\n",
               what.c_str());
  std::exit(2);
}

// The regular files under `p` (recursively), sorted: the order, and so the mutants, are the same
// on every machine. A path that holds no file is an error (a misspelt corpus must not pass).
std::vector<fs::path> files_under(const fs::path& p) {
  std::vector<fs::path> out;
  if (fs::is_directory(p)) {
    for (const auto& e : fs::recursive_directory_iterator(p))
      if (e.is_regular_file() && e.path().filename().string()[0] != '.') out.push_back(e.path());
  } else if (fs::is_regular_file(p)) {
    out.push_back(p);
  }
  if (out.empty()) usage_error(p.string() + ": no input file there");
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  long long mutants = 0;
  std::uint64_t seed = 1;
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--mutants" || a == "--seed") && i + 1 < argc) {
      const std::string v = argv[++i];
      char* end = nullptr;
      const unsigned long long n = std::strtoull(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0') usage_error(a + " " + v + ": not a non-negative integer");
      if (a == "--mutants")
        mutants = static_cast<long long>(n);
      else
        seed = n;
    } else if (a.rfind("--", 0) == 0) {
      usage_error(a + ": unknown option");
    } else {
      for (auto& f : files_under(a)) files.push_back(std::move(f));
    }
  }
  if (files.empty()) usage_error("no input paths");

  const std::string program = fs::path(argv[0]).filename().string();
  install_crash_handler(program + "-crash.json");
  const auto start = std::chrono::steady_clock::now();

  std::vector<std::string> seeds;
  for (const auto& f : files) {
    seeds.push_back(read_file(f));
    run_one(seeds.back(), f.string());
  }
  lsi::fuzz::JsonMutator mutator(seeds, seed);
  for (long long i = 0; i < mutants; ++i) {
    const std::string m = mutator.next();
    run_one(m, "mutant " + std::to_string(i) + " (--seed " + std::to_string(seed) + ")");
  }

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %zu files replayed, %lld mutants (seed %llu), no crash, %.1f s\n",
              program.c_str(), files.size(), mutants, static_cast<unsigned long long>(seed),
              seconds);
  return 0;
}
