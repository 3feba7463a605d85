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


template <class ExecSpace, class MemorySpace>
void evaluate_two_body_batch(const ExecSpace& space, const ClosedFormInputs<MemorySpace>& in,
                             const ClosedFormOutputs<MemorySpace>& out) {
  Kokkos::parallel_for(
      "lsi::two_body_batch", Kokkos::RangePolicy<ExecSpace>(space, 0, in.velocity.extent(0)),
      KOKKOS_LAMBDA(const int i) {
        TwoBodyCoefficients c;
        c.lambda = in.lambda(i);
        c.tau = in.tau(i);
        const TwoBodyImpact imp = two_body_impact(in.landslide_mass(i), in.velocity(i),
                                                  in.equivalent_length(i), in.barrier_mass(i), c);
        out.peak_force(i) = imp.pulse.peak;
        out.rise_time(i) = imp.pulse.rise_time;
        out.impact_duration(i) = imp.pulse.duration;
        out.final_displacement(i) = final_displacement_under(
            imp.pulse, in.barrier_mass(i), in.base_friction(i), in.face_angle(i));
      });
}

template <class ExecSpace, class MemorySpace>
void evaluate_empirical_batch(const ExecSpace& space, const ClosedFormInputs<MemorySpace>& in,
                              const EmpiricalCoefficients& coefficients,
                              const ClosedFormOutputs<MemorySpace>& out) {
  Kokkos::parallel_for(
      "lsi::empirical_batch", Kokkos::RangePolicy<ExecSpace>(space, 0, in.velocity.extent(0)),
      KOKKOS_LAMBDA(const int i) {
        EmpiricalCoefficients c = coefficients;
        c.tau = in.tau(i);
        const EmpiricalImpact imp = empirical_impact(in.thickness(i), in.velocity(i), in.density(i),
                                                     in.landslide_mass(i), in.face_angle(i), c);
        out.peak_force(i) = imp.pulse.peak;
        out.rise_time(i) = imp.pulse.rise_time;
        out.impact_duration(i) = imp.pulse.duration;
        out.final_displacement(i) = final_displacement_under(
            imp.pulse, in.barrier_mass(i), in.base_friction(i), in.face_angle(i));
      });
}

}  // namespace lsi
