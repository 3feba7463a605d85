// The saturated block stopped by a wall (pressure_impulse.hpp) over resolutions, transfers, wall
// conditions and pore-pressure forms: the tables of docs/notes/two_phase.md, "The face jet". Not a test
// (test_mpm_pressure_impulse.cpp asserts); built beside the tests, run by hand, Serial backend.
//
//   pressure_impulse_study [bins]    (bins: also the wall column's velocity per cell)
#include <Kokkos_Core.hpp>
#include <cstdio>
#include <cstring>

#include "pressure_impulse.hpp"
#include "study_space.hpp"

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  using namespace lsi::test::pressure_impulse;
  const bool bins = argc > 1 && std::strcmp(argv[1], "bins") == 0;
  const Block b;
  const double scale = b.impulse_scale(), U = b.speed;
  std::printf("theory: wall impulse %.4f rho_m U H^2, vertical momentum %.4f rho_m U H^2\n",
              theory_wall_impulse(b) / scale, theory_vertical_momentum(b) / scale);
  std::printf(
      "walls | pore pressure | transfer | cells | steps | wall impulse | vertical momentum | "
      "largest wall force in window (rho_m c U H) | corner cell (U) | corner point (U) | "
      "theory's corner cell (U)\n");
  for (bool held : {true, false})
    for (bool cell : {true, false})
      for (Transfer tr : {Transfer::FlipPic, Transfer::Apic})
        for (int cells : {4, 8, 16, 32}) {
          Setup st;
          st.cells = cells, st.transfer = tr, st.held = held, st.cell_pore_pressure = cell;
          const Measured m = impact<lsi::test::StudySpace>(b, st);
          const double dx = b.height / cells;
          if (!m.finished) {
            std::printf("%s | %s | %s | %d | stopped\n", held ? "held" : "unilateral",
                        cell ? "cell" : "point", tr == Transfer::Apic ? "APIC" : "FLIP", cells);
            continue;
          }
          std::printf("%s | %s | %s | %d | %ld | %.4f | %.4f | %.3g | %.3f | %.3f | %.3f\n",
                      held ? "held" : "unilateral", cell ? "cell" : "point",
                      tr == Transfer::Apic ? "APIC" : "FLIP", cells, m.steps,
                      m.wall_impulse / scale, m.vertical_momentum / scale,
                      m.largest_wall_force / (b.mixture_density() * b.wave_speed() * U * b.height),
                      m.wall_velocity.back() / U, m.corner_point_speed / U,
                      theory_vertical_velocity(b, 0, dx, b.height - dx, b.height) / U);
          if (bins)
            for (int j = 0; j < cells; ++j)
              std::printf("  y/H %.3f: v %.4f U, theory %.4f U\n", (j + 0.5) * dx / b.height,
                          m.wall_velocity[j] / U,
                          theory_vertical_velocity(b, 0, dx, j * dx, (j + 1) * dx) / U);
        }
  return 0;
}
