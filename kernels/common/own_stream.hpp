// A stream of the calling host thread's own on a device execution space, for as long as an
// OwnStream lives: the kernels the thread launches through execution_instance.hpp go to it, so
// that runs driven by different host threads overlap on the GPU (model/concurrent_runs.hpp). The
// stream does not wait for the default stream's work, nor it for this one's: what a run shares
// with others is set up before (Kokkos' allocations and its deep copies without an instance
// wait for the whole device). On a host space, or a device backend other than CUDA, an OwnStream
// does nothing; nor where the driver gives no stream: the thread's kernels then stay on the
// default stream, one run after the other, with the same results.
#pragma once
#include <Kokkos_Core.hpp>
#include <optional>
#include <type_traits>

#include "kernels/common/execution_instance.hpp"

namespace lsi {

template <class ExecSpace>
class OwnStream {
 public:
  OwnStream() {
#if defined(KOKKOS_ENABLE_CUDA)
    if constexpr (std::is_same_v<ExecSpace, Kokkos::Cuda>) {
      if (cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking) != cudaSuccess) {
        stream_ = nullptr;
        return;
      }
      previous_ = detail::thread_instance<ExecSpace>();
      detail::thread_instance<ExecSpace>().emplace(stream_);
    }
#endif
  }
  // Waits for the stream's kernels and gives the thread its previous instance back.
  ~OwnStream() {
#if defined(KOKKOS_ENABLE_CUDA)
    if constexpr (std::is_same_v<ExecSpace, Kokkos::Cuda>) {
      if (stream_ == nullptr) return;
      auto& own = detail::thread_instance<ExecSpace>();
      own->fence();
      own = previous_;  // the last copy of the stream's instance goes here
      cudaStreamDestroy(stream_);
    }
#endif
  }
  OwnStream(const OwnStream&) = delete;
  OwnStream& operator=(const OwnStream&) = delete;

 private:
#if defined(KOKKOS_ENABLE_CUDA)
  cudaStream_t stream_ = nullptr;
  std::optional<ExecSpace> previous_;
#endif
};

}  // namespace lsi
