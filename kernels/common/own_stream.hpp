// A stream of the calling host thread's own on a device execution space, for as long as an
// OwnStream lives: the kernels the thread launches through execution_instance.hpp go to it, so
// that runs driven by different host threads overlap on the GPU (model/concurrent_runs.hpp).
// The stream (non-blocking) does not wait for the default stream's work, nor it for this one's.
// What a run reads from elsewhere is ordered by other means: Kokkos' deep copies without an
// instance wait for the whole device, a new View is filled on the default stream and waited
// for, a reduction with a host result waits for its own stream; and the instance's own buffers,
// which Kokkos zeroes on the default stream, are waited for here. On a host space, or a device
// backend other than CUDA, an OwnStream does nothing; nor where CUDA or Kokkos gives no stream:
// the thread's kernels then stay on the default stream, with the same results.
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
      // On Kokkos' device (a thread starts on device 0; KOKKOS_DEVICE_ID may choose another).
      if (cudaSetDevice(Kokkos::Cuda().cuda_device()) != cudaSuccess ||
          cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking) != cudaSuccess) {
        stream_ = nullptr;
        return;
      }
      auto& own = detail::thread_instance<ExecSpace>();
      previous_ = own;
      try {
        own.emplace(stream_);
        Kokkos::fence();  // the instance's buffers, zeroed on the default stream
      } catch (...) {     // no instance: the default stream
        own = previous_;
        cudaStreamDestroy(stream_);
        stream_ = nullptr;
      }
    }
#endif
  }
  // Waits for the stream's kernels and gives the thread its previous instance back. A CUDA
  // error of those kernels is not thrown here (a destructor): it shows at the next wait.
  ~OwnStream() {
#if defined(KOKKOS_ENABLE_CUDA)
    if constexpr (std::is_same_v<ExecSpace, Kokkos::Cuda>) {
      if (stream_ == nullptr) return;
      cudaStreamSynchronize(stream_);
      detail::thread_instance<ExecSpace>() = previous_;  // the stream's last instance goes
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
