// A 2 m x 2 m elastic block in a 4 m x 12 m box without walls, 4 points per cell of 0.25 m: the
// free-fall problem of tests/mpm/test_mpm_free_fall.cpp, shared with the tests that need a
// uniform motion (tests/mpm/test_mpm_transfer_dissipation.cpp).
#pragma once
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"

namespace lsi::test {

template <class Exec>
struct FallingBlock {
  using Mem = typename Exec::memory_space;
  mpm::Material material;
  mpm::Grid<Mem> grid;
  mpm::Particles<Mem> particles;

  FallingBlock() {
    material.density = 2000;
    material.young_modulus = 1e7;
    material.poisson_ratio = 0.3;
    const double lo[2] = {0, 0}, hi[2] = {4, 12}, dx = 0.25;
    grid = mpm::Grid<Mem>(lo, hi, dx);
    mpm::BodySpec body;
    body.polygon = {{{1.0, 9.0}}, {{3.0, 9.0}}, {{3.0, 11.0}}, {{1.0, 11.0}}};
    particles = mpm::build_particles<Mem>({body}, {material}, lo, dx);
  }
  mpm::Solver<Exec> solver(const mpm::Settings& s) const {
    return mpm::Solver<Exec>(grid, particles, {material}, mpm::Boundaries{}, s);
  }
};

}  // namespace lsi::test
