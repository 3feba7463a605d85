// The temporary files of the atomic writers (`<path>.tmp.<pid>`, renamed onto `path` when
// complete) never outlive their writer:
// - while one is being written it is registered; SIGTERM, SIGINT and SIGHUP (what schedulers,
//   Ctrl-C and a closed terminal send) remove every registered temporary before the process
//   ends with the signal's default action (its exit status still says which signal);
// - those of writers that died without a chance to clean up (SIGKILL, a power cut) are removed
//   by the next writer of the same path: a `<path>.tmp.<pid>` whose process no longer exists on
//   this machine is stale.
#pragma once
#include <string>

namespace lsi {

// The temporary name of `path` for this process: `<path>.tmp.<pid>`.
std::string temporary_path(const std::string& path);

// Registers `tmp` for removal on a termination signal for the guard's lifetime (the signal
// handlers are installed on first use). Nesting is allowed; at most 16 at once (further ones are
// not registered and so only removed by the stale-file sweep).
class TemporaryFileGuard {
 public:
  explicit TemporaryFileGuard(const std::string& tmp);
  ~TemporaryFileGuard();
  TemporaryFileGuard(const TemporaryFileGuard&) = delete;
  TemporaryFileGuard& operator=(const TemporaryFileGuard&) = delete;

 private:
  int slot_ = -1;
};

// Removes the regular files `<path>.tmp.<pid>` beside `path` whose process `pid` is not running
// on this machine, and returns how many it removed. Never throws.
int remove_stale_temporaries(const std::string& path) noexcept;

}  // namespace lsi
