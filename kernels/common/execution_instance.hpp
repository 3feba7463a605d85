// The execution space instance that lsi's kernels launch on from the calling host thread, and the
// policies built on it.
//
// On a host space (Serial, OpenMP) this is always the space's default instance: inside a
// campaign's partition (model/concurrent_runs.hpp) that is the partition's own threads, so nothing
// here changes a host run. On a device (CUDA) a host thread that runs a campaign's runs beside
// other threads gives them a stream of its own (own_stream.hpp): the runs' small kernels and
// their reductions' waits then overlap on the GPU instead of queueing on one stream. A thread
// without a stream of its own launches on the default instance.
//
// The device policies carry Kokkos' light-weight hint: Kokkos 3 copies a functor of 512 bytes to
// 32 KiB into one constant-memory buffer that all instances share, through a staging buffer and
// an event that all instances share too, in steps that two host threads can interleave, so two
// streams could run each other's functor; with the hint a functor travels as a kernel argument
// (up to 4 KiB) or in the instance's own global memory.
#pragma once
#include <Kokkos_Core.hpp>
#include <optional>
#include <type_traits>

namespace lsi {

// Whether ExecSpace runs on the host (it can reach host memory).
template <class ExecSpace>
inline constexpr bool runs_on_host =
    Kokkos::SpaceAccessibility<ExecSpace, Kokkos::HostSpace>::accessible;

namespace detail {
// The calling thread's own instance of a device space, where it has one.
template <class ExecSpace>
std::optional<ExecSpace>& thread_instance() {
  static thread_local std::optional<ExecSpace> instance;
  return instance;
}
}  // namespace detail

// The instance the calling thread's kernels launch on.
template <class ExecSpace>
ExecSpace execution_instance() {
  if constexpr (!runs_on_host<ExecSpace>) {
    if (const auto& own = detail::thread_instance<ExecSpace>()) return *own;
  }
  return ExecSpace();
}

// The threads that the calling thread's kernels on ExecSpace run on: inside a partition of
// Kokkos 3's OpenMP backend (model/concurrent_runs.hpp, model/run_threads.hpp) the partition's,
// which ExecSpace().concurrency() does not tell there (it gives the whole pool's).
template <class ExecSpace>
int instance_concurrency() {
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
  if constexpr (std::is_same_v<ExecSpace, Kokkos::OpenMP>)
    return Kokkos::OpenMP::impl_thread_pool_size();
#endif
  return ExecSpace().concurrency();
}

// Points begin .. end - 1 on the calling thread's instance.
template <class ExecSpace, class Begin, class End>
auto range_policy(const Begin begin, const End end) {
  if constexpr (runs_on_host<ExecSpace>) {
    return Kokkos::RangePolicy<ExecSpace>(begin, end);
  } else {
    return Kokkos::Experimental::require(
        Kokkos::RangePolicy<ExecSpace>(execution_instance<ExecSpace>(), begin, end),
        Kokkos::Experimental::WorkItemProperty::HintLightWeight);
  }
}

// `league` teams of `team_size` threads on the calling thread's instance.
template <class ExecSpace, class League>
auto team_policy(const League league, const int team_size) {
  if constexpr (runs_on_host<ExecSpace>) {
    return Kokkos::TeamPolicy<ExecSpace>(league, team_size);
  } else {
    return Kokkos::Experimental::require(
        Kokkos::TeamPolicy<ExecSpace>(execution_instance<ExecSpace>(), league, team_size),
        Kokkos::Experimental::WorkItemProperty::HintLightWeight);
  }
}

// view = value for every element, ordered with the calling thread's kernels on ExecSpace.
template <class ExecSpace, class View, class Value>
void fill(const View& view, const Value& value) {
  if constexpr (runs_on_host<ExecSpace>) {
    Kokkos::deep_copy(view, value);
  } else {
    Kokkos::deep_copy(execution_instance<ExecSpace>(), view, value);
  }
}

// to = from between host and device once the calling thread's kernels on ExecSpace are done;
// returns when `to` holds the values (and `from` may be changed).
template <class ExecSpace, class To, class From>
void copy_and_wait(const To& to, const From& from) {
  if constexpr (runs_on_host<ExecSpace>) {
    Kokkos::deep_copy(to, from);
  } else {
    const ExecSpace instance = execution_instance<ExecSpace>();
    Kokkos::deep_copy(instance, to, from);
    instance.fence();
  }
}

}  // namespace lsi
