// The closed-form part of a sweep: for each sample of a chunk, draw its inputs
// (sweeps/sampler.hpp), set them into the base scene values, check the scene
// (sweeps/sampled_scene.hpp) and evaluate the empirical and/or analytical model, batched
// (kernels/closed_form/batch.hpp). No allocation and no I/O per sample: the caller owns the
// output Views and copies them out once per chunk.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>
#include <vector>

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

// Whether the checks of a sweep's samples are of single fields, each against its own range: no
// face check and no top width against the base width (the host's block path below).
inline bool checks_of_single_fields(const SampleChecks& c) {
  if (c.face) return false;
  for (int k = 0; k < c.field_count; ++k)
    if (c.fields[k] == top_width_m) return false;
  return true;
}

// The host's block path (evaluate_closed_form_chunk): first[k] = f for the samples k < count
// whose value v[k] of field f fails its check (value_invalid, sampled_scene.hpp). A function of
// its own, its loop reading only its parameters: GCC vectorises it.
inline void mark_invalid(const int count, const double* __restrict v, const FieldRange r,
                         const bool positive_invalid, const int f, int* __restrict first) {
  for (int k = 0; k < count; ++k)
    first[k] = value_invalid(v[k], r, positive_invalid) ? f : first[k];
}

// The models' inputs of a block of samples: one column each (ClosedFormChunkColumns).
struct BlockModelInputs {
  double *thickness, *velocity, *density, *landslide_mass, *equivalent_length, *barrier_mass,
      *base_friction, *face_angle, *empirical_tau, *analytical_tau, *analytical_lambda;
};

// model_inputs (sampled_scene.hpp), term for term, of the samples k < count <= B of a block
// whose scene field f is col[f][k]; the scene's kind from `base`. The kind's choices are made
// before the loops (a selection on a bool in the loop keeps GCC from vectorising it), each
// value that depends on the kind into a column of its own; then one loop over the samples.
template <int B>
void block_model_inputs(const int count, const double* const* col, const SceneValues& base,
                        const TwoBodyCoefficients defaults, const BlockModelInputs out) {
  const double* const h = col[thickness_m];
  double length[B], barrier_mass[B], tau[B], lambda[B];
  const double* L = col[length_m];
  if (!base.rectangle) {
    const double* const squares = col[body_squares];
    for (int k = 0; k < count; ++k) length[k] = (2.0 + squares[k]) * h[k];
    L = length;
  }
  const double* m2 = col[barrier_mass_kg_per_m];
  if (base.fixed) {
    for (int k = 0; k < count; ++k) barrier_mass[k] = unbounded;
    m2 = barrier_mass;
  } else if (!base.barrier_given_by_mass) {
    const double *const bw = col[base_width_m], *const tw = col[top_width_m],
                        *const height = col[height_m], *const rho2 = col[barrier_density_kg_m3];
    for (int k = 0; k < count; ++k) {
      const double area = 0.5 * (bw[k] + tw[k]) * height[k];
      barrier_mass[k] = rho2[k] * area;
    }
    m2 = barrier_mass;
  }
  const double* a_tau = col[sweeps::analytical_tau];
  if (!base.analytical_tau_given) {
    for (int k = 0; k < count; ++k) tau[k] = defaults.tau;
    a_tau = tau;
  }
  const double* a_lambda = col[sweeps::analytical_lambda];
  if (!base.analytical_lambda_given) {
    for (int k = 0; k < count; ++k) lambda[k] = defaults.lambda;
    a_lambda = lambda;
  }
  const double *const v = col[velocity_m_s], *const rho = col[density_kg_m3],
                      *const mu = col[base_friction], *const beta = col[face_angle_deg],
                      *const e_tau = col[sweeps::empirical_tau];
#pragma GCC ivdep
  for (int k = 0; k < count; ++k) {
    out.thickness[k] = h[k];
    out.velocity[k] = v[k];
    out.density[k] = rho[k];
    out.landslide_mass[k] = rho[k] * L[k] * h[k];
    out.equivalent_length[k] = L[k];
    out.barrier_mass[k] = m2[k];
    out.base_friction[k] = mu[k];
    out.face_angle[k] = math::degrees_to_radians(beta[k]);
    out.empirical_tau[k] = e_tau[k];
    out.analytical_tau[k] = a_tau[k];
    out.analytical_lambda[k] = a_lambda[k];
  }
}

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
    if (batch && !empirical_one && !analytical_one && checks_of_single_fields(checks)) {
      // What one_sample does, a block of samples at a time in loops over the block's samples
      // that the compiler vectorises: each scene field a column of the block (a sampled field's
      // the sampler's, the others the base value repeated), the checks field by field from the
      // last (the first invalid field overwrites the later ones), the models' inputs. The same
      // operations on the same values as one_sample: the same bits.
      constexpr int B = Sampler<MemorySpace>::block_size;
      std::vector<double> repeated(std::size_t(scene_field_count) * B);
      for (int f = 0; f < scene_field_count; ++f)
        for (int k = 0; k < B; ++k) repeated[std::size_t(f) * B + k] = sweep.base.value[f];
      const double* const base_columns = repeated.data();
      const SceneValues& base = sweep.base;
      const TwoBodyCoefficients defaults = default_two_body_coefficients(base.fixed);
      const auto each_block = [&](const std::size_t i0, const int count, const double* x) {
        const double* col[scene_field_count];
        for (int f = 0; f < scene_field_count; ++f) col[f] = base_columns + f * B;
        for (int d = 0; d < dims; ++d) {
          double* const in = &inputs(i0, d);
#pragma GCC ivdep
          for (int k = 0; k < count; ++k) in[k] = x[d * B + k];
          if (sweep.target[d] >= 0) col[sweep.target[d]] = x + d * B;
        }
        int bad[B];
        for (int k = 0; k < count; ++k) bad[k] = -1;
        for (int c = checks.field_count - 1; c >= 0; --c) {
          const int f = checks.fields[c];
          if (!field_unused(base, f))
            mark_invalid(count, col[f], scene_field_range(f),
                         f == empirical_kappa && base.empirical_momentum, f, bad);
        }
        int* const invalid = &invalid_field(i0);
        for (int k = 0; k < count; ++k) invalid[k] = bad[k];
        BlockModelInputs out;
        out.thickness = &thickness(i0);
        out.velocity = &velocity(i0);
        out.density = &density(i0);
        out.landslide_mass = &landslide_mass(i0);
        out.equivalent_length = &equivalent_length(i0);
        out.barrier_mass = &barrier_mass(i0);
        out.base_friction = &friction(i0);
        out.face_angle = &face_angle(i0);
        out.empirical_tau = &empirical_tau(i0);
        out.analytical_tau = &analytical_tau(i0);
        out.analytical_lambda = &analytical_lambda(i0);
        block_model_inputs<B>(count, col, base, defaults, out);
      };
      draw_sample_blocks_on_host(space, sweep.sampler, first, n, each_block);
    } else {
      // Not for_each_block_on_host: its `flatten` inlines the momentum variants' scalar models
      // into the block, and GCC's code there gives other last bits than the same models called
      // on their own (which the kernel's test compares bit for bit).
      draw_blocks_on_host(space, sweep.sampler, first, n, sweep.base, one_sample);
    }
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
