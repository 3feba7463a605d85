// Runs a shell command and returns its exit code and standard output: how the end-to-end tests
// run the `lsi` executable (redirect stderr in the command, e.g. "2>&1", to capture it too).
#pragma once
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

namespace lsi::testing {

struct CommandOutcome {
  int code;         // exit code, -1 if the command did not exit normally
  std::string out;  // what it wrote on standard output
};

inline CommandOutcome run_command(const std::string& command) {
  FILE* p = popen(command.c_str(), "r");
  if (!p) return {-1, "popen failed"};
  std::string out;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// Runs `lsi args` (`lsi` the executable's path) with its standard output and error together in
// `out`; `env`, assignments before the command (e.g. "OMP_NUM_THREADS=1"), may be empty.
inline CommandOutcome run_lsi(const std::string& lsi, const std::string& args,
                              const std::string& env = "") {
  return run_command((env.empty() ? "" : env + " ") + lsi + " " + args + " 2>&1");
}

// Starts `argv` (argv[0] the program) in a child process with its standard output and error
// discarded, and returns the child's pid (for tests that signal or kill a run part-way).
inline pid_t spawn_quietly(const std::vector<std::string>& argv) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  const int null = ::open("/dev/null", O_WRONLY);
  dup2(null, 1);
  dup2(null, 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  execv(args[0], args.data());
  _exit(127);
}

}  // namespace lsi::testing
