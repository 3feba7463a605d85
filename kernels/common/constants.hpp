#pragma once

namespace lsi {
// Gravitational acceleration g (m/s^2) used by every model.
inline constexpr double gravity = 9.81;
}  // namespace lsi
