// The footprint of an MPM case; see mpm_footprint.hpp.
#include "model/mpm_footprint.hpp"

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>

#include "model/concurrent_runs.hpp"
#include "model/host_threads.hpp"
#include "model/mpm_impact.hpp"
#include "model/run_threads.hpp"
#include "model/input_error.hpp"
#include "model/messages.hpp"
#include "model/resource_estimate.hpp"
#include "kernels/mpm/two_phase/two_phase_time_step.hpp"

namespace lsi {
namespace {

// Bytes per point and per node: the fields of particles.hpp and grid.hpp (two_phase_*.hpp for the
// saturated case) rounded up, and per node and thread the duplicated scatter's copies of the
// fields P2G adds to (none with the atomic scatter).
constexpr double kDryPointBytes = 8.0 * 24, kSaturatedPointBytes = 8.0 * 40;
constexpr double kDryNodeBytes = 8.0 * 12, kSaturatedNodeBytes = 8.0 * 28;
constexpr double kDryScatterNodeBytes = 8.0 * 5, kSaturatedScatterNodeBytes = 8.0 * 10;
// One output of the histories (about 40 series and the impact vectors), and one snapshot point
// (16 doubles with the pore pressure, its id and material).
constexpr double kOutputBytes = 8.0 * 64, kSnapshotPointBytes = 8.0 * 18;
// Whether a run's state lives in host memory (the default memory space is the host's): the
// state of a device run is not counted against the host's memory.
constexpr bool kStateOnHost =
    Kokkos::SpaceAccessibility<Kokkos::HostSpace,
                               Kokkos::DefaultExecutionSpace::memory_space>::accessible;

double polygon_area(const std::vector<std::array<double, 2>>& p) {
  double twice = 0.0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % n];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * std::fabs(twice);
}

std::string number(double v) { return format_number(v); }
// A derived number, to three digits.
std::string approx(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

MpmFootprint estimate_footprint(const MpmCase& c) {
  MpmFootprint f;
  const MpmSettings& s = c.settings;
  const double dx = s.cell_size_m;
  double wave_speed = 0.0, speed = 0.0;
  for (const auto& b : c.bodies) {
    const double per_cell = double(b.points_per_cell_direction) * b.points_per_cell_direction;
    f.points += polygon_area(b.polygon) / (dx * dx) * per_cell;
    speed = std::max(speed, std::hypot(b.velocity[0], b.velocity[1]));
  }
  for (const auto& m : c.materials) {
    double w = m.wave_speed();
    if (c.two_phase) {
      const double M = m.lame_lambda() + 2.0 * m.shear_modulus();
      w = mpm::two_phase::saturated_wave_speed(M, m.density, c.two_phase->porosity,
                                               c.two_phase->liquid.density,
                                               c.two_phase->liquid.bulk_modulus);
    }
    wave_speed = std::max(wave_speed, w);
  }
  f.nodes = (std::floor((c.upper[0] - c.lower[0]) / dx + 0.5) + 1.0) *
            (std::floor((c.upper[1] - c.lower[1]) / dx + 0.5) + 1.0);
  const bool saturated = c.two_phase.has_value();
  // The host scatter's copies of the grid: one per thread of the run (model/run_threads.hpp).
  const double copies = s.atomic_scatter ? 0.0
                        : runs_on_one_thread(static_cast<long>(f.points), saturated)
                            ? 1.0
                            : static_cast<double>(host_thread_count());
  f.state_bytes =
      f.points * (saturated ? kSaturatedPointBytes : kDryPointBytes) +
      f.nodes * ((saturated ? kSaturatedNodeBytes : kDryNodeBytes) +
                 copies * (saturated ? kSaturatedScatterNodeBytes : kDryScatterNodeBytes));
  f.history_bytes = (s.end_time_s / s.output_interval_s + 1.0) * kOutputBytes;
  if (s.snapshot_interval_s > 0.0)
    f.snapshot_bytes =
        (s.end_time_s / s.snapshot_interval_s + 2.0) * f.points * kSnapshotPointBytes;
  f.first_time_step = std::min(s.courant * dx / (wave_speed + speed), s.max_time_step_s);
  f.max_steps = s.end_time_s / f.first_time_step;
  return f;
}

double host_run_bytes(const MpmFootprint& f) {
  return (kStateOnHost ? f.state_bytes : 0.0) + f.history_bytes + f.snapshot_bytes;
}

double scene_run_bytes(const Scene& s) {
  try {
    return host_run_bytes(estimate_footprint(impact_case(s)));
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception&) {
    return 0.0;
  }
}

int campaign_runs_that_fit(const std::size_t tasks, const std::vector<const Scene*>& scenes) {
  const int runs = concurrent_runs(tasks);
  if (runs < 2) return runs;
  double largest = 0.0;
  for (const Scene* s : scenes) largest = std::max(largest, scene_run_bytes(*s));
  return runs_that_fit(runs, largest, available_memory_bytes());
}

void check_mpm_fits(const MpmCase& c) {
  const std::uint64_t have = available_memory_bytes();
  if (have == 0) return;
  const MpmFootprint f = estimate_footprint(c);
  const MpmSettings& s = c.settings;
  const double room = static_cast<double>(have);
  // The state lives in the default memory space: checked here only when that is the host's.
  const double state = kStateOnHost ? f.state_bytes : 0.0;
  const std::string counts = approx(f.points) + " points and " + approx(f.nodes) + " nodes";
  if (state > room)
    require_fits("methods.mpm.cell_size_m", number(s.cell_size_m), "the MPM state (" + counts + ")",
                 state, have, "memory",
                 "a cell of at least " + approx(s.cell_size_m * std::sqrt(state / room) * 1.01) +
                     " m fits, or a smaller domain");
  if (state + f.snapshot_bytes > room) {
    const double fit = (room - state) / (f.points * kSnapshotPointBytes) - 2.0;
    require_fits("methods.mpm.snapshot_interval_s", number(s.snapshot_interval_s),
                 "snapshots of " + approx(f.points) +
                     " points to end_time_s = " + number(s.end_time_s) + " s",
                 state + f.snapshot_bytes, have, "memory",
                 fit >= 1.0
                     ? "a snapshot_interval_s of at least " + approx(s.end_time_s / fit) + " s fits"
                     : "the state leaves no room for snapshots: leave them out");
  }
  if (state + f.snapshot_bytes + f.history_bytes > room) {
    const double outputs = (room - state - f.snapshot_bytes) / kOutputBytes - 1.0;
    require_fits("methods.mpm.end_time_s", number(s.end_time_s),
                 "the histories of a run to end_time_s (one output every output_interval_s = " +
                     approx(s.output_interval_s) + " s)",
                 state + f.snapshot_bytes + f.history_bytes, have, "memory",
                 "an end_time_s of at most " +
                     approx(std::max(outputs, 1.0) * s.output_interval_s) +
                     " s or a longer output_interval_s fits; an impact run ends at rest before it");
  }
}

}  // namespace lsi
