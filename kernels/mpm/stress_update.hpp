// Stress update (after G2P, "update stress last"): with L the velocity gradient of the step,
// d eps = sym(L) dt and spin w = (L_xy - L_yx)/2; the stress is rotated (Jaumann), incremented
// elastically and, for Mohr-Coulomb materials, returned to the yield surface. The volume follows
// det(I + L dt). Instantiated with or without plasticity so that an elastic scene pays nothing
// for it.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/constitutive/jaumann.hpp"
#include "kernels/mpm/constitutive/linear_elastic.hpp"
#include "kernels/mpm/constitutive/mohr_coulomb.hpp"
#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

template <class ExecSpace, bool WithPlasticity, class MemorySpace>
void stress_update(const Particles<MemorySpace>& p,
                   const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials, double dt) {
  Kokkos::parallel_for(
      WithPlasticity ? "lsi::mpm::stress_update_plastic" : "lsi::mpm::stress_update_elastic",
      Kokkos::RangePolicy<ExecSpace>(0, p.count), KOKKOS_LAMBDA(const int q) {
        const PreparedMaterial& m = materials(p.material(q));
        const double Lxx = p.velocity_gradient(q, 0, 0), Lxy = p.velocity_gradient(q, 0, 1),
                     Lyx = p.velocity_gradient(q, 1, 0), Lyy = p.velocity_gradient(q, 1, 1);
        const double de[3] = {Lxx * dt, Lyy * dt, 0.5 * (Lxy + Lyx) * dt};
        double s[4] = {p.stress(q, 0), p.stress(q, 1), p.stress(q, 2), p.stress(q, 3)};
        jaumann_rotate(s, 0.5 * (Lxy - Lyx), dt);
        elastic_increment(m, de, s);
        if constexpr (WithPlasticity) {
          if (m.material.model == Material::Model::MohrCoulomb)
            p.plastic_work(q) += p.volume(q) * mohr_coulomb_return(m, s);
        }
        for (int k = 0; k < 4; ++k) p.stress(q, k) = s[k];
        // Volume: J of the step; equivalent deviatoric strain increment (plane strain).
        const double J = (1.0 + Lxx * dt) * (1.0 + Lyy * dt) - Lxy * Lyx * dt * dt;
        p.volume(q) *= J;
        const double em = (de[0] + de[1]) / 3.0;
        const double d0 = de[0] - em, d1 = de[1] - em, d2 = -em;
        p.deviatoric_strain(q) +=
            math::sqrt(2.0 / 3.0 * (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * de[2] * de[2]));
      });
}

}  // namespace lsi::mpm
