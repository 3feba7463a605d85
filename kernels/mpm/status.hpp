// How a solver step or run ended, and its one-line description (printed by the CLI).
#pragma once

namespace lsi::mpm {

enum class Status { Running, Finished, NonFinite, LeftGrid, TimeStepCollapse, EnergyGrowth };

inline const char* describe(Status s) {
  switch (s) {
    case Status::Running:
      return "running";
    case Status::Finished:
      return "finished";
    case Status::NonFinite:
      return "unstable: non-finite velocity or position";
    case Status::LeftGrid:
      return "unstable: a material point left the grid";
    case Status::TimeStepCollapse:
      return "unstable: the time step collapsed";
    case Status::EnergyGrowth:
      return "unstable: the total energy grew";
  }
  return "?";
}

}  // namespace lsi::mpm
