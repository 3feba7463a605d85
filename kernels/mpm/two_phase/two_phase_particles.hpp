// Two-phase (saturated soil) material points, single-point formulation (the paper's section 3.3;
// Jassim et al. 2013): each point is a volume V of the mixture and carries both phases.
// The solid skeleton reuses the single-phase SoA (`solid`): position (moves with the solid),
// solid velocity, APIC affine matrix, solid velocity gradient, EFFECTIVE stress sigma' (tension
// positive), SOLID mass m_S = (1 - n0) rho_S V0, mixture volume V, plastic work, ... so that the
// single-phase stress update (Jaumann + elastic / Mohr-Coulomb) and energy kernels apply to it
// unchanged. The liquid fields are added here; a dry scene never allocates them.
// Sign convention: pore pressure p is COMPRESSION POSITIVE; total stress sigma = sigma' - p I.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/particles.hpp"

namespace lsi::mpm::two_phase {

// A field added here must also be moved by the sort (TwoPhaseSolver::sort_points).
template <class MemorySpace>
struct TwoPhaseParticles {
  int count = 0;
  Particles<MemorySpace> solid;                                         // skeleton (see above)
  Kokkos::View<double* [2], PointLayout, MemorySpace> liquid_velocity;  // m/s
  Kokkos::View<double* [2][2], PointLayout, MemorySpace>
      liquid_affine;  // APIC C of the liquid, 1/s
  // div v_L, 1/s: of the last step where a pass after the G2P reads it (as the solid's
  // velocity gradient, particles.hpp: the separate pore pressure update).
  Kokkos::View<double*, MemorySpace> liquid_divergence;
  Kokkos::View<double*, MemorySpace> liquid_mass;    // kg/m, m_L = n0 rho_L V0 (constant)
  Kokkos::View<double*, MemorySpace> porosity;       // n, current
  Kokkos::View<double*, MemorySpace> pore_pressure;  // Pa, compression positive
  Kokkos::View<double*, MemorySpace> conductivity;   // hydraulic conductivity k, m/s
  Kokkos::View<double* [2], PointLayout, MemorySpace> traction;  // N/m, surface load on the point
                                                                 // (applied to the mixture)
  // Artificial bulk viscosity (pore_pressure_update.hpp): the mixture's volumetric strain rate
  // D = (1 - n) tr(L_S) + n div(v_L) of the last step, 1/s, and
  // the viscous pressure q(D) >= 0 (Pa, compression positive) it gives. q acts in P2G beside p
  // (p + q in both the mixture and the liquid force) but is never added to p.
  Kokkos::View<double*, MemorySpace> volumetric_rate;   // 1/s
  Kokkos::View<double*, MemorySpace> viscous_pressure;  // Pa

  TwoPhaseParticles() = default;
  explicit TwoPhaseParticles(int n) : count(n), solid(n) {
    liquid_velocity = decltype(liquid_velocity)("p_liquid_velocity", n);
    liquid_affine = decltype(liquid_affine)("p_liquid_affine", n);
    liquid_divergence = decltype(liquid_divergence)("p_liquid_divergence", n);
    liquid_mass = decltype(liquid_mass)("p_liquid_mass", n);
    porosity = decltype(porosity)("p_porosity", n);
    pore_pressure = decltype(pore_pressure)("p_pore_pressure", n);
    conductivity = decltype(conductivity)("p_conductivity", n);
    traction = decltype(traction)("p_traction", n);
    volumetric_rate = decltype(volumetric_rate)("p_volumetric_rate", n);
    viscous_pressure = decltype(viscous_pressure)("p_viscous_pressure", n);
  }
};

// The fields of host TwoPhaseParticles as raw component arrays with the same element access,
// for loops over points that the compiler is to vectorise (as PointArrays, particles.hpp, of
// which `solid` is one).
struct TwoPhasePointArrays {
  PointArrays solid;
  PointColumns<2> liquid_velocity, traction;
  PointMatrices liquid_affine;
  PointColumn<double> liquid_divergence, liquid_mass, porosity, pore_pressure, conductivity,
      volumetric_rate, viscous_pressure;

  template <class MemorySpace>
  KOKKOS_FORCEINLINE_FUNCTION explicit TwoPhasePointArrays(const TwoPhaseParticles<MemorySpace>& p)
      : solid(p.solid),
        liquid_divergence{p.liquid_divergence.data()},
        liquid_mass{p.liquid_mass.data()},
        porosity{p.porosity.data()},
        pore_pressure{p.pore_pressure.data()},
        conductivity{p.conductivity.data()},
        volumetric_rate{p.volumetric_rate.data()},
        viscous_pressure{p.viscous_pressure.data()} {
    // Written out, as in PointArrays: each pointer a value of its own.
    liquid_velocity = {{&p.liquid_velocity(0, 0), &p.liquid_velocity(0, 1)}};
    traction = {{&p.traction(0, 0), &p.traction(0, 1)}};
    liquid_affine = {{{&p.liquid_affine(0, 0, 0), &p.liquid_affine(0, 0, 1)},
                      {&p.liquid_affine(0, 1, 0), &p.liquid_affine(0, 1, 1)}}};
  }
};

// The pore liquid, one per solver (SI).
struct Liquid {
  double density = 1000.0;      // rho_L, kg/m^3
  double bulk_modulus = 2.2e9;  // K_L, Pa
};

}  // namespace lsi::mpm::two_phase
