// Host work that several threads share outside the Kokkos kernels: a sweep table's chunks
// compressed, its output columns described. Where the build has OpenMP it runs on the OpenMP
// runtime's threads, so that it is placed as the user places them (OMP_PROC_BIND, OMP_PLACES, a
// launcher's binding): with a binding, the runtime binds the program's first thread to one CPU,
// and threads started with std::thread inherit that one CPU and would all share it.
#pragma once
#include <cstddef>
#include <functional>

namespace lsi {

// The threads host work may use: the OpenMP runtime's (OMP_NUM_THREADS, else the CPUs the program
// may run on); without OpenMP, OMP_NUM_THREADS when set, else the hardware's. At least 1.
std::size_t host_thread_count();

// Calls worker(t) once on each of up to n threads at the same time (at least the calling
// thread, whose t is 0). Fewer may join (inside a parallel region, down to the caller alone),
// so the workers share their work through what they capture (an atomic counter of items), never
// by waiting for a worker that has not started. An exception from a worker is rethrown once
// every worker has returned (the one of the smallest t).
void on_host_threads(std::size_t n, const std::function<void(std::size_t)>& worker);

}  // namespace lsi
