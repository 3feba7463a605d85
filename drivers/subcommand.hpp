// A subcommand of `lsi` defined in its own file: main() registers it, and after parsing runs the
// one the user chose inside its error handling (InputError: exit 2, other exceptions: exit 1).
#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace lsi {

struct Subcommand {
  CLI::App* command = nullptr;   // owned by the parent app
  std::function<int()> run;      // returns the exit code
};

Subcommand add_sweep_command(CLI::App& app);       // drivers/sweep_command.cpp
Subcommand add_merge_command(CLI::App& app);       // drivers/sweep_command.cpp
Subcommand add_calibrate_command(CLI::App& app);   // drivers/calibrate_command.cpp
Subcommand add_accuracy_command(CLI::App& app);    // drivers/accuracy_command.cpp

}  // namespace lsi
