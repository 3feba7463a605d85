// Memory and disk a run may take; see resource_estimate.hpp.
#include "model/resource_estimate.hpp"

#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/input_error.hpp"
#include "model/messages.hpp"

namespace lsi {
namespace {

namespace fs = std::filesystem;

// The first number on the line of /proc/meminfo that starts with `key` (kB), or 0.
std::uint64_t meminfo_kib(const std::string& key) {
  std::ifstream f("/proc/meminfo");
  for (std::string line; std::getline(f, line);)
    if (line.compare(0, key.size(), key) == 0) {
      std::istringstream in(line.substr(key.size()));
      std::uint64_t v = 0;
      in >> v;
      return v;
    }
  return 0;
}

// A cgroup's limit minus its use, from the first file pair that exists (v2, then v1); 0 when
// unlimited or unknown.
std::uint64_t cgroup_room() {
  const char* pairs[][2] = {{"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"},
                            {"/sys/fs/cgroup/memory/memory.limit_in_bytes",
                             "/sys/fs/cgroup/memory/memory.usage_in_bytes"}};
  for (const auto& p : pairs) {
    std::ifstream lim(p[0]), use(p[1]);
    std::string limit_text;
    std::uint64_t used = 0;
    if (!(lim >> limit_text) || !(use >> used)) continue;
    if (limit_text == "max") return 0;
    std::uint64_t limit = 0;
    try {
      limit = std::stoull(limit_text);
    } catch (...) {
      return 0;
    }
    if (limit >= (std::uint64_t(1) << 60)) return 0;  // v1 writes "unlimited" as a huge number
    return limit > used ? limit - used : 1;
  }
  return 0;
}

// The address space left under this process's limit (ulimit -v), 0 when unlimited or unknown.
std::uint64_t address_space_room() {
  struct rlimit lim {};
  if (::getrlimit(RLIMIT_AS, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return 0;
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  if (!(statm >> pages)) return 0;
  const std::uint64_t used = pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  return lim.rlim_cur > used ? lim.rlim_cur - used : 1;
}

}  // namespace

std::uint64_t available_memory_bytes() {
  std::uint64_t room = 0;  // 0: no bound known yet
  for (const std::uint64_t bound :
       {meminfo_kib("MemAvailable:") * 1024, cgroup_room(), address_space_room()})
    if (bound != 0) room = room == 0 ? bound : std::min(room, bound);
  return room;
}

std::uint64_t free_disk_bytes(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(path), ec);
  if (ec) return 0;
  p = p.parent_path();
  while (!p.empty() && !fs::is_directory(p, ec)) {
    if (p == p.parent_path()) return 0;
    p = p.parent_path();
  }
  struct statvfs st {};
  if (p.empty() || ::statvfs(p.c_str(), &st) != 0) return 0;
  return static_cast<std::uint64_t>(st.f_bavail) * st.f_frsize;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"bytes", "kiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return buf;
}

void require_fits(const std::string& field, const std::string& value, const std::string& what,
                  double need, std::uint64_t have, const std::string& kind,
                  const std::string& remedy) {
  if (have == 0 || need <= static_cast<double>(have)) return;
  throw InputError(field + " = " + value + ": " + what + " would take about " + format_bytes(need) +
                   " of " + kind + ", " + format_bytes(static_cast<double>(have)) + " available (" +
                   remedy + ")");
}

}  // namespace lsi
