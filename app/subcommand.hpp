// A subcommand of `lsi` defined in its own file: main() registers it, and after parsing runs the
// one the user chose inside its error handling (InputError: exit 2, other exceptions: exit 1).
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

#include "io/json_fields.hpp"

namespace lsi {

struct Subcommand {
  CLI::App* command = nullptr;  // owned by the parent app
  std::function<int()> run;     // returns the exit code
};

Subcommand add_sweep_command(CLI::App& app);      // app/sweep_command.cpp
Subcommand add_merge_command(CLI::App& app);      // app/sweep_command.cpp
Subcommand add_calibrate_command(CLI::App& app);  // app/calibrate_command.cpp
Subcommand add_accuracy_command(CLI::App& app);   // app/accuracy_command.cpp

// An option given with an empty value (`--out ''`, `--methods ''`) is an input error, not the
// option left out: throws InputError naming the first such option of `app` or of the subcommands
// that were parsed.
inline void reject_empty_values(const CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->count() == 0 || o->get_expected_min() == 0) continue;  // not given, or a flag
    for (const std::string& v : o->results())
      if (v.empty())
        json_fields::fail(o->get_name() + " = \"\": must not be empty (" + o->get_description() +
                          ")");
  }
  for (const CLI::App* sub : app.get_subcommands()) reject_empty_values(*sub);
}

}  // namespace lsi
