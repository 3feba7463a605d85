// The closed-form part of a sweep in one Kokkos kernel: for each sample of a chunk, draw its
// inputs (sweeps/sampler.hpp), set them into the base scene values, check the scene
// (sweeps/sampled_scene.hpp) and evaluate the empirical and/or analytical model. No allocation
// and no I/O per sample: the caller owns the output Views and copies them out once per chunk.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>

#include "sweeps/sampled_scene.hpp"
#include "sweeps/sampler.hpp"

namespace lsi::sweeps {

template <class MemorySpace>
struct ClosedFormSweep {
  static constexpr int max_inputs = Sampler<MemorySpace>::max_dimensions;
  explicit ClosedFormSweep(Sampler<MemorySpace> s) : sampler(std::move(s)) {}
  Sampler<MemorySpace> sampler;
  SceneValues base;
  int target[max_inputs] = {};  // scene field set by each input (-1: read only by the MPM)
  bool empirical = false, analytical = false;
};

// Columns of `outputs`: empirical peak_force .. final_displacement, then analytical's (a method
// not run leaves its columns untouched). `invalid_field(i)` = first invalid scene field of
// sample first+i, or -1; the outputs of an invalid sample are NaN.
template <class ExecSpace, class MemorySpace>
void evaluate_closed_form_chunk(
    const ExecSpace& space, const ClosedFormSweep<MemorySpace>& sweep, std::uint64_t first,
    const Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>& inputs,
    const Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>& outputs,
    const Kokkos::View<int*, MemorySpace>& invalid_field) {
  const int dims = sweep.sampler.dimensions();
  Kokkos::parallel_for(
      "lsi::closed_form_sweep", Kokkos::RangePolicy<ExecSpace>(space, 0, invalid_field.extent(0)),
      KOKKOS_LAMBDA(const std::size_t i) {
        double x[ClosedFormSweep<MemorySpace>::max_inputs];
        sweep.sampler.sample(first + i, x);
        SceneValues s = sweep.base;
        for (int d = 0; d < dims; ++d) {
          inputs(i, d) = x[d];
          if (sweep.target[d] >= 0) s.value[sweep.target[d]] = x[d];
        }
        const int bad = first_invalid_field(s);
        invalid_field(i) = bad;
        double out[closed_form_output_count];
        if (sweep.empirical) {
          if (bad < 0) evaluate_empirical(s, out);
          for (int o = 0; o < closed_form_output_count; ++o)
            outputs(i, o) = bad < 0 ? out[o] : math::quiet_nan();
        }
        if (sweep.analytical) {
          if (bad < 0) evaluate_analytical(s, out);
          for (int o = 0; o < closed_form_output_count; ++o)
            outputs(i, closed_form_output_count + o) = bad < 0 ? out[o] : math::quiet_nan();
        }
      });
}

}  // namespace lsi::sweeps
