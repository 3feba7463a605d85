// Large host columns on transparent huge pages. A sweep's table and the copies its statistics
// sort hold tens of millions of values; on 4 KiB pages each column costs one page fault per
// 4 KiB at its first write, and on a virtual machine those faults take more time than the
// writes themselves. Where the kernel gives transparent huge pages only to memory that asks
// for them (THP "madvise", a common default), these helpers ask: madvise(MADV_HUGEPAGE) on a
// buffer before anything is written to it, so that it faults 2 MiB at a time. Only a hint: the
// values and their layout are the same with or without it, and on other systems, with THP off
// or for buffers under 2 MiB nothing changes.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lsi::sweeps {

// Asks for huge pages for the whole 2 MiB pages inside [data, data + bytes); the pages already
// written keep their size. Errors are ignored (a hint).
inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t huge = std::uintptr_t{1} << 21;
  const auto first = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t begin = (first + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (first + bytes) & ~(huge - 1);
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

// The same for the whole allocation of a Kokkos View in host-accessible memory; nothing for
// another memory space (a GPU's).
template <class View>
void advise_huge_pages(const View& v) {
  if constexpr (Kokkos::SpaceAccessibility<Kokkos::HostSpace,
                                           typename View::memory_space>::accessible)
    advise_huge_pages(v.data(), v.span() * sizeof(typename View::value_type));
}

// v.reserve(n), with new storage advised before the values are moved into it.
template <class T>
void reserve_on_huge_pages(std::vector<T>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  std::vector<T> w;
  w.reserve(n);
  advise_huge_pages(w.data(), n * sizeof(T));
  w.insert(w.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
  v.swap(w);
}

// n copies of `value` in new storage advised before they are written.
template <class T>
std::vector<T> vector_on_huge_pages(std::size_t n, const T& value = T()) {
  std::vector<T> v;
  reserve_on_huge_pages(v, n);
  v.assign(n, value);
  return v;
}

}  // namespace lsi::sweeps
