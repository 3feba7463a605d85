// Batched evaluation of the closed-form models over arrays of inputs (one Kokkos kernel per
// model; no allocation, no I/O): the entry point of Monte Carlo and calibration sweeps. Inputs
// and outputs are flat structure-of-arrays Views in the execution space's memory.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/closed_form/barrier_sliding.hpp"
#include "kernels/closed_form/empirical_model.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/two_body_model.hpp"
#include "kernels/common/execution_instance.hpp"
#include "kernels/common/simd_lanes.hpp"

namespace lsi {

template <class MemorySpace>
struct ClosedFormInputs {
  using View = Kokkos::View<const double*, MemorySpace>;
  View thickness;          // h, m
  View velocity;           // v0, m/s
  View density;            // rho_m, kg/m^3
  View landslide_mass;     // m1, kg/m
  View equivalent_length;  // L1,0, m
  View barrier_mass;       // m2, kg/m (+infinity: fixed barrier)
  View base_friction;      // tan(delta_b)
  View face_angle;         // beta, rad
  View tau;                // T1/T2
  View lambda;             // s1,max/L1,0 (analytical model only)
};

template <class MemorySpace>
struct ClosedFormOutputs {
  using View = Kokkos::View<double*, MemorySpace>;
  View peak_force;          // N/m, normal to the face
  View rise_time;           // s
  View impact_duration;     // s
  View final_displacement;  // m (0 for a fixed barrier, +infinity if it never stops)
};

// The batches' loop over samples. On a GPU one thread a sample; on the host in blocks of
// kSamplesPerBlock consecutive samples, the loop over a block marked free of dependencies between
// samples so that GCC evaluates the models for a vector register of samples at once (the models
// are written without branches or library calls for that: barrier_sliding.hpp, sliding_block.hpp,
// sincos_first_quadrant.hpp, pow_nonnegative.hpp; and the build passes -fno-math-errno). The last,
// partial block runs one sample at a time. 64: with 8 (one AVX-512 register) GCC 12 unrolled the loop of the OpenMP
// instantiation and left it scalar, 7x slower (docs/notes/performance.md, "Closed-form models").
// `#pragma omp simd` is not used: GCC turns the models' local structs into per-lane arrays before
// inlining, and then does not vectorise.
constexpr int kSamplesPerBlock = 64;

// The body of a block is inlined whole (GCC's `flatten`): the vectoriser needs the model's code in
// the loop, and GCC's inliner stops at a body the size of the empirical model's.
#if defined(__GNUC__) && !defined(__CUDACC__)
#define LSI_FLATTEN __attribute__((flatten))
#else
#define LSI_FLATTEN
#endif

// On the host: full_block(begin) for every full block of kSamplesPerBlock samples from begin,
// one_sample(i) for each sample of the last, partial block; blocks in parallel.
template <class ExecSpace, class FullBlock, class OneSample>
void for_each_block_on_host(const char* name, const ExecSpace& space, int n,
                            const FullBlock& full_block, const OneSample& one_sample) {
  const int blocks = (n + kSamplesPerBlock - 1) / kSamplesPerBlock;
  Kokkos::parallel_for(name, Kokkos::RangePolicy<ExecSpace>(space, 0, blocks),
                       [=](const int block) LSI_FLATTEN {
                         const int begin = block * kSamplesPerBlock;
                         if (begin + kSamplesPerBlock <= n) {
                           full_block(begin);
                         } else {
                           for (int i = begin; i < n; ++i) one_sample(i);
                         }
                       });
}

// Runs body(i) for every sample i in [0, n), as above.
template <class ExecSpace, class Body>
void for_each_sample(const char* name, const ExecSpace& space, int n, const Body& body) {
  if constexpr (!runs_on_host<ExecSpace>) {
    Kokkos::parallel_for(name, Kokkos::RangePolicy<ExecSpace>(space, 0, n), body);
  } else {
    for_each_block_on_host(
        name, space, n,
        [=](const int begin) {
#if defined(__clang__)
#pragma clang loop vectorize(assume_safety)
#elif defined(__GNUC__)
#pragma GCC ivdep
#endif
          for (int k = 0; k < kSamplesPerBlock; ++k) body(begin + k);
        },
        body);
  }
}

template <class ExecSpace, class MemorySpace>
void evaluate_two_body_batch(const ExecSpace& space, const ClosedFormInputs<MemorySpace>& in,
                             const ClosedFormOutputs<MemorySpace>& out) {
  for_each_sample(
      "lsi::two_body_batch", space, int(in.velocity.extent(0)), KOKKOS_LAMBDA(const int i) {
        TwoBodyCoefficients c;
        c.lambda = in.lambda(i);
        c.tau = in.tau(i);
        const TwoBodyImpact imp = two_body_impact(in.landslide_mass(i), in.velocity(i),
                                                  in.equivalent_length(i), in.barrier_mass(i), c);
        out.peak_force(i) = imp.pulse.peak;
        out.rise_time(i) = imp.pulse.rise_time;
        out.impact_duration(i) = imp.pulse.duration;
        out.final_displacement(i) = final_displacement_under(imp.pulse, in.barrier_mass(i),
                                                             in.base_friction(i), in.face_angle(i));
      });
}

template <class ExecSpace, class MemorySpace>
void evaluate_empirical_batch(const ExecSpace& space, const ClosedFormInputs<MemorySpace>& in,
                              const EmpiricalCoefficients& coefficients,
                              const ClosedFormOutputs<MemorySpace>& out) {
  // The model's second half (eqs. 2-7 and the barrier's motion) for sample i from its approach
  // and Fr^a2.
  const auto finish = [=] KOKKOS_FUNCTION(const int i, const EmpiricalApproach& approach,
                                          const double froude_power) {
    EmpiricalCoefficients c = coefficients;
    c.tau = in.tau(i);
    const EmpiricalImpact imp = empirical_impact(approach, froude_power, in.thickness(i),
                                                 in.density(i), in.landslide_mass(i), c);
    out.peak_force(i) = imp.pulse.peak;
    out.rise_time(i) = imp.pulse.rise_time;
    out.impact_duration(i) = imp.pulse.duration;
    out.final_displacement(i) = final_displacement_under(imp.pulse, in.barrier_mass(i),
                                                         in.base_friction(i), in.face_angle(i));
  };
  const auto sample = KOKKOS_LAMBDA(const int i) {
    const EmpiricalApproach a =
        empirical_approach(in.thickness(i), in.velocity(i), in.face_angle(i));
    finish(i, a, math::pow_nonnegative(a.froude, coefficients.a2));
  };
  const int n = int(in.velocity.extent(0));
#if LSI_HOST_SIMD_LANES
  if constexpr (runs_on_host<ExecSpace>) {
    // A block in three passes: the approaches (vectorised by GCC), Fr^a2 eight lanes at a time
    // (pow_nonnegative_each: the tables read by register permutes, which GCC's own vectorisation
    // of pow_nonnegative turns into scalar loads), the rest (vectorised by GCC). Same bits as
    // `sample`.
    for_each_block_on_host(
        "lsi::empirical_batch", space, n,
        [=](const int begin) {
          double normal_velocity[kSamplesPerBlock], tangential_velocity[kSamplesPerBlock];
          double froude[kSamplesPerBlock], froude_power[kSamplesPerBlock];
#pragma GCC ivdep
          for (int k = 0; k < kSamplesPerBlock; ++k) {
            const int i = begin + k;
            const EmpiricalApproach a =
                empirical_approach(in.thickness(i), in.velocity(i), in.face_angle(i));
            normal_velocity[k] = a.normal_velocity;
            tangential_velocity[k] = a.tangential_velocity;
            froude[k] = a.froude;
          }
          math::pow_nonnegative_each(froude, coefficients.a2, froude_power, kSamplesPerBlock);
#pragma GCC ivdep
          for (int k = 0; k < kSamplesPerBlock; ++k) {
            EmpiricalApproach a;
            a.normal_velocity = normal_velocity[k];
            a.tangential_velocity = tangential_velocity[k];
            a.froude = froude[k];
            finish(begin + k, a, froude_power[k]);
          }
        },
        sample);
    return;
  }
#endif
  for_each_sample("lsi::empirical_batch", space, n, sample);
}

}  // namespace lsi
