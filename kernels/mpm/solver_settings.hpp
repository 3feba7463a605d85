// The settings both MPM solvers read; the dry (solver.hpp, Settings) and the saturated
// (two_phase/two_phase_solver.hpp, TwoPhaseSettings) solver each add their own.
#pragma once
#include <limits>

#include "kernels/common/constants.hpp"
#include "kernels/mpm/g2p.hpp"

namespace lsi::mpm {

struct SolverSettings {
  double courant = 0.5;
  double max_time_step = std::numeric_limits<double>::infinity();  // s
  double min_time_step = 1e-12;                                    // s; below: collapse
  double gravity[2] = {0.0, -lsi::gravity};                        // body force, m/s^2
  Transfer transfer = Transfer::Apic;  // APIC, or a FLIP/PIC blend without affine terms
  double flip_ratio = 0.99;            // FlipPic only: share of FLIP, [0, 1] (0: plain PIC)
  bool atomic_scatter = false;         // P2G with atomics instead of per-thread buffers (p2g.hpp)
  // Points per tile of the atomic P2G (P2GScatter::tile_points): -1 the default (128 on a
  // device from 50 000 points on, none on the host), 0 none, n > 0 tiles of n points at any
  // size. A knob of the benchmarks and tests.
  int scatter_tile_points = -1;
  // Before the first step and every this many steps the points are sorted by grid cell
  // (sort_points.hpp), so that neighbours in space stay neighbours in memory as the flow mixes
  // them; 0: never. A sort of points that are in order already costs one pass over their
  // positions and leaves them as they are.
  int sort_interval = 50;
  double energy_growth_limit = 0.5;  // relative growth of the total energy deemed unstable
  // Account the kinetic energy lost in the grid transfers (transfer_dissipation.hpp): a few
  // reductions a step, off by default.
  bool track_transfer_dissipation = false;
  // > 0: the walls' normal load is also booked in bands of this length along each wall (m;
  // wall_bands.hpp), taken with SolverBase::take_wall_band_impulse.
  double wall_band = 0.0;
};

}  // namespace lsi::mpm
