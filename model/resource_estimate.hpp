// What a run needs against what the machine has: memory (the smallest of the memory the kernel
// reports available, the cgroup's limit left, as under a batch scheduler or a container, and the
// address space left under the process's limit, ulimit -v) and
// free disk space where a result goes. A sweep or an MPM run that cannot fit is refused before it
// starts (InputError naming the field and the numbers), instead of failing hours later.
#pragma once
#include <cstdint>
#include <string>

namespace lsi {

// Bytes of memory this process may still take (0 if unknown: then nothing is refused on it).
std::uint64_t available_memory_bytes();

// Bytes free for an unprivileged writer on the file system that would hold `path` (its nearest
// existing ancestor directory); 0 if unknown.
std::uint64_t free_disk_bytes(const std::string& path);

// "1.5 GiB", "312 MiB", "20 kiB": for messages.
std::string format_bytes(double bytes);

// Throws InputError("<field> = <value>: <what> would take about <need> of <kind>, <have>
// available (<remedy>)") when `need` exceeds `have` (a `have` of 0 means unknown and passes).
void require_fits(const std::string& field, const std::string& value, const std::string& what,
                  double need, std::uint64_t have, const std::string& kind,
                  const std::string& remedy);

}  // namespace lsi
