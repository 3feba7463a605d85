// Temporary files that never outlive their writer; see temporary_files.hpp.
#include "io/temporary_files.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>

namespace lsi {
namespace {

namespace fs = std::filesystem;

constexpr int kSlots = 16;
constexpr std::size_t kPathBytes = 4096;
// A slot is free (0), being filled or emptied (1), or holds a path to remove (2). The handler
// reads only slots in state 2, whose path is complete and stays so until the guard ends.
std::atomic<int> slot_state[kSlots];
char slot_path[kSlots][kPathBytes];
constexpr int kSignals[] = {SIGTERM, SIGINT, SIGHUP};

extern "C" void remove_temporaries_and_reraise(int sig) {
  const int saved = errno;
  for (int i = 0; i < kSlots; ++i)
    if (slot_state[i].load(std::memory_order_acquire) == 2) ::unlink(slot_path[i]);
  // The default action, with the signal's own exit status (a scheduler sees "terminated").
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  sigset_t unblock;
  sigemptyset(&unblock);
  sigaddset(&unblock, sig);
  ::pthread_sigmask(SIG_UNBLOCK, &unblock, nullptr);
  ::raise(sig);
  errno = saved;  // reached only if the default action does not end the process
}

// Installs the handler for each signal whose disposition is still the default: a signal the user
// ignores (nohup) or that another library handles is left alone.
void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int sig : kSignals) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL ||
          (old.sa_flags & SA_SIGINFO) != 0)
        continue;
      struct sigaction sa {};
      sa.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&sa.sa_mask);
      for (const int other : kSignals) sigaddset(&sa.sa_mask, other);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

bool all_digits(const std::string& s) {
  if (s.empty() || s.size() > 10) return false;
  for (const char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

}  // namespace

std::string temporary_path(const std::string& path) {
  return path + ".tmp." + std::to_string(::getpid());
}

TemporaryFileGuard::TemporaryFileGuard(const std::string& tmp) {
  install_handlers();
  if (tmp.size() >= kPathBytes) return;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!slot_state[i].compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) continue;
    std::memcpy(slot_path[i], tmp.c_str(), tmp.size() + 1);
    slot_state[i].store(2, std::memory_order_release);
    slot_ = i;
    return;
  }
}

TemporaryFileGuard::~TemporaryFileGuard() {
  if (slot_ >= 0) slot_state[slot_].store(0, std::memory_order_release);
}

int remove_stale_temporaries(const std::string& path) noexcept {
  int removed = 0;
  try {
    const fs::path target(path);
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string prefix = target.filename().string() + ".tmp.";
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string pid_text = name.substr(prefix.size());
      if (!all_digits(pid_text)) continue;
      const long pid = std::stol(pid_text);
      if (pid <= 0 || pid == ::getpid()) continue;
      if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)
        continue;  // alive, or not ours to judge
      std::error_code e2;
      if (!fs::is_regular_file(it->symlink_status(e2)) || e2) continue;
      if (fs::remove(it->path(), e2)) ++removed;
    }
  } catch (...) {
  }
  return removed;
}

}  // namespace lsi
