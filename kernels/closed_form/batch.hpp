// Batched evaluation of the closed-form models over arrays of inputs (one Kokkos kernel per
// model; no allocation, no I/O): the entry point of Monte Carlo and calibration sweeps. Inputs
// and outputs are flat structure-of-arrays Views in the execution space's memory.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/closed_form/barrier_sliding.hpp"
#include "kernels/closed_form/empirical_model.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/two_body_model.hpp"

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

// Runs body(i) for every sample i in [0, n). On a GPU one thread a sample; on the host in blocks of
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

template <class ExecSpace, class Body>
void for_each_sample(const char* name, const ExecSpace& space, int n, const Body& body) {
  constexpr bool host =
      Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename ExecSpace::memory_space>::accessible;
  if constexpr (!host) {
    Kokkos::parallel_for(name, Kokkos::RangePolicy<ExecSpace>(space, 0, n), body);
  } else {
    const int blocks = (n + kSamplesPerBlock - 1) / kSamplesPerBlock;
    Kokkos::parallel_for(name, Kokkos::RangePolicy<ExecSpace>(space, 0, blocks),
                         [=](const int block) LSI_FLATTEN {
                           const int begin = block * kSamplesPerBlock;
                           if (begin + kSamplesPerBlock <= n) {
#if defined(__clang__)
#pragma clang loop vectorize(assume_safety)
#elif defined(__GNUC__)
#pragma GCC ivdep
#endif
                             for (int k = 0; k < kSamplesPerBlock; ++k) body(begin + k);
                           } else {
                             for (int i = begin; i < n; ++i) body(i);
                           }
                         });
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
  for_each_sample(
      "lsi::empirical_batch", space, int(in.velocity.extent(0)), KOKKOS_LAMBDA(const int i) {
        EmpiricalCoefficients c = coefficients;
        c.tau = in.tau(i);
        const EmpiricalImpact imp = empirical_impact(in.thickness(i), in.velocity(i), in.density(i),
                                                     in.landslide_mass(i), in.face_angle(i), c);
        out.peak_force(i) = imp.pulse.peak;
        out.rise_time(i) = imp.pulse.rise_time;
        out.impact_duration(i) = imp.pulse.duration;
        out.final_displacement(i) = final_displacement_under(imp.pulse, in.barrier_mass(i),
                                                             in.base_friction(i), in.face_angle(i));
      });
}

}  // namespace lsi
