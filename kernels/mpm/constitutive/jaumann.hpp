// Objective (Jaumann) stress rate, the paper's eq. 23 with large rotations:
//   sigma_dot = D : eps_dot + W sigma - sigma W,   W = (L - L^T) / 2
// In 2D plane strain W has one component, w = W_xy = (L_xy - L_yx) / 2, and the rotation terms are
//   d(sxx) = 2 w sxy dt,  d(syy) = -2 w sxy dt,  d(sxy) = w (syy - sxx) dt,  d(szz) = 0.
#pragma once
#include <Kokkos_Macros.hpp>

namespace lsi::mpm {

KOKKOS_INLINE_FUNCTION void jaumann_rotate(double s[4], double spin_xy, double dt) {
  const double sxx = s[0], syy = s[1], sxy = s[2];
  s[0] = sxx + 2.0 * spin_xy * sxy * dt;
  s[1] = syy - 2.0 * spin_xy * sxy * dt;
  s[2] = sxy + spin_xy * (syy - sxx) * dt;
}

}  // namespace lsi::mpm
