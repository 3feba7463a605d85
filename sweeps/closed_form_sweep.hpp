// The closed-form part of a sweep: for each sample of a chunk, draw its inputs
// (sweeps/sampler.hpp), set them into the base scene values, check the scene
// (sweeps/sampled_scene.hpp) and evaluate the empirical and/or analytical model, batched
// (kernels/closed_form/batch.hpp). No allocation and no I/O per sample: the caller owns the
// output Views and copies them out once per chunk.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>

#include "kernels/closed_form/batch.hpp"
#include "sweeps/huge_pages.hpp"
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

// The model inputs of a chunk's samples, one column each, for the batched models
// (kernels/closed_form/batch.hpp); kept by the caller from chunk to chunk.
template <class MemorySpace>
struct ClosedFormChunkColumns {
  using Column = Kokkos::View<double*, MemorySpace>;
  static constexpr int count = 11;
  Column column[count];
  // At least n rows in every column (new ones are not filled: every row used is written; on
  // huge pages where they are host memory, sweeps/huge_pages.hpp).
  void reserve(std::size_t n) {
    if (column[0].extent(0) >= n) return;
    for (auto& c : column) {
      c = Column(Kokkos::view_alloc(Kokkos::WithoutInitializing, "lsi::closed_form_sweep column"),
                 n);
      advise_huge_pages(c);
    }
  }
};

namespace detail {
// The columns of ClosedFormChunkColumns.
enum ChunkColumn : int {
  thickness_column,
  velocity_column,
  density_column,
  landslide_mass_column,
  equivalent_length_column,
  barrier_mass_column,
  base_friction_column,
  face_angle_column,
  empirical_tau_column,
  analytical_tau_column,
  analytical_lambda_column
};

// Whether a method runs batched: the paper's barrier model (the momentum-consistent one runs a
// sample at a time), and for the empirical model its a1, a2 and kappa not sampled (the batch
// takes one set).
inline bool empirical_batched(const SceneValues& base, const int* targets, int n) {
  if (base.empirical_momentum) return false;
  for (int d = 0; d < n; ++d)
    if (targets[d] == empirical_a1 || targets[d] == empirical_a2 || targets[d] == empirical_kappa)
      return false;
  return true;
}
}  // namespace detail

// Columns of `outputs`: empirical peak_force .. final_displacement, then analytical's (a method
// not run leaves its columns untouched). `invalid_field(i)` = first invalid scene field of
// sample first+i, or -1; the outputs of an invalid sample are NaN. One kernel draws the samples,
// checks them (only what sampling can change: sample_checks) and writes the models' inputs into
// `columns`; the models then run batched (vectorised on the host: batch.hpp), except a
// momentum-consistent variant or an empirical model with sampled coefficients, which the first
// kernel evaluates a sample at a time. The outputs are the same as the scalar models' (the
// batches evaluate the same functions).
template <class ExecSpace, class MemorySpace>
void evaluate_closed_form_chunk(
    const ExecSpace& space, const ClosedFormSweep<MemorySpace>& sweep, std::uint64_t first,
    const Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>& inputs,
    const Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>& outputs,
    const Kokkos::View<int*, MemorySpace>& invalid_field,
    ClosedFormChunkColumns<MemorySpace>& columns) {
  using namespace detail;
  const int dims = sweep.sampler.dimensions();
  const std::size_t n = invalid_field.extent(0);
  if (n == 0) return;
  const SampleChecks checks = sample_checks(sweep.base, sweep.target, dims);
  const bool empirical_batch = sweep.empirical && empirical_batched(sweep.base, sweep.target, dims);
  const bool analytical_batch = sweep.analytical && !sweep.base.analytical_momentum;
  const bool empirical_one = sweep.empirical && !empirical_batch;
  const bool analytical_one = sweep.analytical && !analytical_batch;
  const bool batch = empirical_batch || analytical_batch;
  using Column = typename ClosedFormChunkColumns<MemorySpace>::Column;
  Column col[ClosedFormChunkColumns<MemorySpace>::count];
  if (batch) {
    columns.reserve(n);
    for (int k = 0; k < ClosedFormChunkColumns<MemorySpace>::count; ++k)
      col[k] = Column(columns.column[k].data(), n);
  }
  const Column thickness = col[thickness_column], velocity = col[velocity_column],
               density = col[density_column], landslide_mass = col[landslide_mass_column],
               equivalent_length = col[equivalent_length_column],
               barrier_mass = col[barrier_mass_column], friction = col[base_friction_column],
               face_angle = col[face_angle_column], empirical_tau = col[empirical_tau_column],
               analytical_tau = col[analytical_tau_column],
               analytical_lambda = col[analytical_lambda_column];
  // Sample i from its inputs x[d * stride] (d < dims): set into the scene s (the base scene's
  // values but the sampled ones, which are set here), checked, and the models' inputs written
  // (or the models evaluated, for what does not run batched).
  const auto one_sample =
      KOKKOS_LAMBDA(SceneValues & s, const std::size_t i, const double* x, const int stride) {
    for (int d = 0; d < dims; ++d) {
      inputs(i, d) = x[d * stride];
      if (sweep.target[d] >= 0) s.value[sweep.target[d]] = x[d * stride];
    }
    const int bad = first_invalid_field(s, checks);
    invalid_field(i) = bad;
    if (batch) {
      const ModelInputs m = model_inputs(s);
      thickness(i) = s.value[thickness_m];
      velocity(i) = s.value[velocity_m_s];
      density(i) = s.value[density_kg_m3];
      landslide_mass(i) = m.landslide_mass;
      equivalent_length(i) = m.equivalent_length;
      barrier_mass(i) = m.barrier_mass;
      friction(i) = s.value[base_friction];
      face_angle(i) = m.face_angle_rad;
      empirical_tau(i) = s.value[sweeps::empirical_tau];
      TwoBodyCoefficients c = default_two_body_coefficients(s.fixed);
      if (s.analytical_lambda_given) c.lambda = s.value[sweeps::analytical_lambda];
      if (s.analytical_tau_given) c.tau = s.value[sweeps::analytical_tau];
      analytical_tau(i) = c.tau;
      analytical_lambda(i) = c.lambda;
    }
    double out[closed_form_output_count];
    if (empirical_one) {
      if (bad < 0) evaluate_empirical(s, out);
      for (int o = 0; o < closed_form_output_count; ++o)
        outputs(i, o) = bad < 0 ? out[o] : math::quiet_nan();
    }
    if (analytical_one) {
      if (bad < 0) evaluate_analytical(s, out);
      for (int o = 0; o < closed_form_output_count; ++o)
        outputs(i, closed_form_output_count + o) = bad < 0 ? out[o] : math::quiet_nan();
    }
  };
  if constexpr (runs_on_host<ExecSpace>) {
    // Not for_each_block_on_host: its `flatten` inlines the momentum variants' scalar models
    // into the block, and GCC's code there gives other last bits than the same models called on
    // their own (which the kernel's test compares bit for bit).
    draw_blocks_on_host(space, sweep.sampler, first, n, sweep.base, one_sample);
  } else {
    Kokkos::parallel_for(
        "lsi::closed_form_sweep", Kokkos::RangePolicy<ExecSpace>(space, 0, n),
        KOKKOS_LAMBDA(const std::size_t i) {
          double x[ClosedFormSweep<MemorySpace>::max_inputs];
          sweep.sampler.sample(first + i, x);
          SceneValues s = sweep.base;
          one_sample(s, i, x, 1);
        });
  }
  if (!batch) return;
  // Column o of `outputs` (LayoutLeft: contiguous).
  auto output_column = [&](int o) {
    return typename ClosedFormOutputs<MemorySpace>::View(outputs.data() + o * outputs.stride(1), n);
  };
  auto outputs_from = [&](int offset) {
    ClosedFormOutputs<MemorySpace> o;
    o.peak_force = output_column(offset + sweeps::peak_force);
    o.rise_time = output_column(offset + sweeps::rise_time);
    o.impact_duration = output_column(offset + sweeps::impact_duration);
    o.final_displacement = output_column(offset + sweeps::final_displacement);
    return o;
  };
  ClosedFormInputs<MemorySpace> in;
  in.thickness = thickness;
  in.velocity = velocity;
  in.density = density;
  in.landslide_mass = landslide_mass;
  in.equivalent_length = equivalent_length;
  in.barrier_mass = barrier_mass;
  in.base_friction = friction;
  in.face_angle = face_angle;
  in.lambda = analytical_lambda;
  if (empirical_batch) {
    EmpiricalCoefficients c;
    c.a1 = sweep.base.value[empirical_a1];
    c.a2 = sweep.base.value[empirical_a2];
    c.kappa = sweep.base.value[empirical_kappa];
    in.tau = empirical_tau;
    evaluate_empirical_batch(space, in, c, outputs_from(0));
  }
  if (analytical_batch) {
    in.tau = analytical_tau;
    evaluate_two_body_batch(space, in, outputs_from(closed_form_output_count));
  }
  // An invalid sample's outputs are NaN.
  const int from = empirical_batch ? 0 : closed_form_output_count;
  const int to = analytical_batch ? 2 * closed_form_output_count : closed_form_output_count;
  Kokkos::parallel_for(
      "lsi::closed_form_sweep_invalid", Kokkos::RangePolicy<ExecSpace>(space, 0, n),
      KOKKOS_LAMBDA(const std::size_t i) {
        if (invalid_field(i) < 0) return;
        for (int o = from; o < to; ++o) outputs(i, o) = math::quiet_nan();
      });
}

// The same, with columns of its own (allocated for this call).
template <class ExecSpace, class MemorySpace>
void evaluate_closed_form_chunk(
    const ExecSpace& space, const ClosedFormSweep<MemorySpace>& sweep, std::uint64_t first,
    const Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>& inputs,
    const Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>& outputs,
    const Kokkos::View<int*, MemorySpace>& invalid_field) {
  ClosedFormChunkColumns<MemorySpace> columns;
  evaluate_closed_form_chunk(space, sweep, first, inputs, outputs, invalid_field, columns);
}

}  // namespace lsi::sweeps
