// The output loop of a solver run, shared by the dry and the saturated solver: steps to
// end_time, calling on_output at t = 0, every output_interval and at the end; checks the energy
// growth at each output; asks `done` after each output whether the run may end early (then the
// status is Finished). The last step is clamped to end_time through the solver's maximum time
// step, which gets the user's value back afterwards.
#pragma once
#include <algorithm>
#include <functional>

#include "kernels/mpm/status.hpp"

namespace lsi::mpm {

// step(): one step, returns its Status; energy_grew(): the growth check at an output.
template <class SolverT, class Step, class EnergyGrew>
Status run_loop(const SolverT& solver, double end_time, double output_interval,
                double& max_time_step, double user_max_time_step, double min_time_step, Step&& step,
                EnergyGrew&& energy_grew, const std::function<void(const SolverT&)>& on_output,
                const std::function<bool(const SolverT&)>& done) {
  if (on_output) on_output(solver);
  double next_output = solver.time() + output_interval;
  struct Restore {
    double& value;
    double user;
    ~Restore() { value = user; }
  } restore{max_time_step, user_max_time_step};
  // A leftover shorter than the collapse threshold is not a step worth taking.
  const double close_enough = std::max(1e-12 * end_time, min_time_step);
  while (end_time - solver.time() > close_enough) {
    max_time_step = std::min(user_max_time_step, end_time - solver.time());
    const Status s = step();
    if (s != Status::Running) return s;
    const double t = solver.time();
    if (t >= next_output * (1 - 1e-12) || end_time - t <= close_enough) {
      next_output += output_interval;
      if (energy_grew()) return Status::EnergyGrowth;
      if (on_output) on_output(solver);
      if (done && done(solver)) break;
    }
  }
  return Status::Finished;
}

}  // namespace lsi::mpm
