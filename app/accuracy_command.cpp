// `lsi accuracy STUDY --out DIR`: runs an accuracy study (app/accuracy_study.hpp) and writes
// DIR/accuracy.json and DIR/accuracy.md; each run keeps DIR/runs/<series>-<k>.h5 (its histories)
// and DIR/runs/<series>-<k>.json (its record, written last), so that `--resume` after a kill
// reruns only the runs without a record for the same scene. app/lsi_accuracy_plot.py draws the
// work-precision diagrams from accuracy.json (ci/accuracy.sh runs both).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/accuracy_study.hpp"
#include "io/hdf5_results.hpp"
#include "io/json_fields.hpp"
#include "io/output_paths.hpp"
#include "app/subcommand.hpp"
#include "io/text_file.hpp"

namespace lsi {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// A previous run's record for exactly this scene, if any.
bool load_record(const fs::path& file, const json& scene, AccuracyRun& run) {
  std::ifstream f(file);
  if (!f) return false;
  try {
    const json j = json::parse(f);
    if (j.at("scene") != scene) return false;
    run = accuracy_run_from_json(j.at("run"));
    return true;
  } catch (const json::exception&) {
    return false;  // unreadable: run again
  }
}

std::string describe_run(const AccuracyRun& r, const std::vector<std::string>& outputs) {
  std::ostringstream s;
  s << r.status << ", " << r.steps << " steps, " << r.solver_seconds << " s";
  for (const auto& o : outputs) {
    const auto it = r.outputs.find(o);
    if (it != r.outputs.end()) s << ", " << o << " " << json_fields::format_number(it->second);
  }
  return s.str();
}

}  // namespace

Subcommand add_accuracy_command(CLI::App& app) {
  struct Args {
    std::string study, out = "results/accuracy";
    std::vector<std::string> only;
    bool resume = false;
  };
  auto args = std::make_shared<Args>();
  Subcommand s;
  s.command = app.add_subcommand(
      "accuracy",
      "Run an accuracy study (docs/reference/scene_schema.md, \"Accuracy studies\"): MPM "
      "series refining the cell size, points per cell or Courant number; observed "
      "order, Richardson extrapolation, GCI, and the error of every run and of the "
      "closed forms against run time (docs/vv/accuracy.md)");
  s.command->add_option("study", args->study, "Accuracy study JSON file")->required();
  s.command->add_option("--out", args->out, "Output directory (default results/accuracy)");
  s.command->add_flag("--resume", args->resume,
                      "Reuse the finished runs of an earlier, interrupted run of the same study");
  s.command->add_option("--only", args->only,
                        "Run only these series (by name); the others are "
                        "reused from their records and must exist");
  s.run = [args] {
    const AccuracyStudy study = load_accuracy_study(args->study);
    for (const auto& name : args->only)
      if (std::none_of(study.series.begin(), study.series.end(),
                       [&](const AccuracySeries& x) { return x.name == name; }))
        throw InputError("--only \"" + name + "\": no such series in " + args->study);
    check_output_directory("--out", args->out);
    const fs::path out(args->out), runs_dir = out / "runs";
    fs::create_directories(runs_dir);
    std::vector<std::vector<AccuracyRun>> runs(study.series.size());
    for (size_t i = 0; i < study.series.size(); ++i) {
      const AccuracySeries& series = study.series[i];
      const bool selected = args->only.empty() || std::find(args->only.begin(), args->only.end(),
                                                            series.name) != args->only.end();
      std::vector<double> values = series.values;  // coarse (cheap) first
      std::sort(values.begin(), values.end(), [&](double a, double b) {
        return accuracy_spacing(series.parameter, a) > accuracy_spacing(series.parameter, b);
      });
      for (const double v : values) {
        const json scene = accuracy_run_scene(study, series, v);
        const std::string stem =
            (runs_dir / (series_file_stem(series.name) + "-" + series.parameter + "-" +
                         json_fields::format_number(v)))
                .string();
        AccuracyRun run;
        if ((args->resume || !selected) && load_record(stem + ".json", scene, run)) {
          std::cerr << "[accuracy] " << series.name << ", " << series.parameter << " = " << v
                    << ": kept from " << stem << ".json\n";
        } else if (!selected) {
          throw InputError("series \"" + series.name +
                           "\" was left out by --only but has no "
                           "record for " +
                           series.parameter + " = " + json_fields::format_number(v) + " in " +
                           runs_dir.string());
        } else {
          run = run_accuracy_case(scene, series, v);
          write_results(stem + ".h5", scene, {run.result});
          write_text_atomically(stem + ".json",
                                json{{"scene", scene}, {"run", to_json(run)}}.dump(1) + "\n");
          std::cerr << "[accuracy] " << series.name << ", " << series.parameter << " = " << v
                    << ": " << describe_run(run, series.outputs) << "\n";
        }
        runs[i].push_back(std::move(run));
      }
    }
    const json report = accuracy_report(study, runs, time_closed_forms(study));
    write_text_atomically((out / "accuracy.json").string(), report.dump(1) + "\n");
    const std::string md = accuracy_markdown(report);
    write_text_atomically((out / "accuracy.md").string(), md);
    std::cout << md;
    return 0;
  };
  return s;
}

}  // namespace lsi
