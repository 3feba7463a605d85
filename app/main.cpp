// `lsi`: the command line. Scenes in (JSON), summaries out (table or JSON), results in HDF5.
// Exit codes: 0 success, 2 invalid input (scene, options), 3 an MPM run stopped unstable (what it
// computed is still written), 1 any other failure (I/O, ...).
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>

#include "model/closed_form_methods.hpp"
#include "io/convergence_file.hpp"
#include "io/hdf5_results.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "io/mpm_snapshots.hpp"
#include "io/mpm_scene.hpp"
#include "app/openmp_wait_policy.hpp"
#include "io/output_paths.hpp"
#include "io/provenance.hpp"
#include "io/report.hpp"
#include "io/resolved_scene.hpp"
#include "model/scene.hpp"
#include "model/scene_methods.hpp"
#include "app/subcommand.hpp"
#include "io/text_file.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time
#include "io/scene_overrides.hpp"
#include "model/concurrent_runs.hpp"
#include "model/mpm_footprint.hpp"
#include "model/design_verify.hpp"
#include "model/run_threads.hpp"
#include "model/progress.hpp"
#include "io/scene_parser.hpp"

namespace {

constexpr const char* known_methods[] = {"empirical", "analytical", "literature", "mpm"};

std::vector<std::string> parse_methods(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  for (std::string m; std::getline(ss, m, ',');) {
    if (m.empty()) continue;
    bool ok = false;
    for (const char* k : known_methods) ok = ok || m == k;
    if (!ok)
      throw lsi::InputError("--methods " + m +
                            ": unknown method (allowed: empirical, "
                            "analytical, literature, mpm)");
    out.push_back(m);
  }
  if (!list.empty() && out.empty()) throw lsi::InputError("--methods: empty list");
  return out;
}

// Loads a scene; validation errors (which name only the JSON path) get the file name in front,
// so that `lsi compare` with many scenes says which file is wrong.
template <class F>
auto with_path(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const lsi::InputError& e) {
    const std::string what = e.what();
    if (what.rfind(path, 0) == 0) throw;
    throw lsi::InputError(path + ": " + what);
  }
}

// The scene document of a file with the command line's --set overrides applied.
nlohmann::json scene_document(const std::string& path, const std::vector<std::string>& overrides) {
  nlohmann::json doc = lsi::read_scene_document(path);
  with_path(path, [&] {
    lsi::apply_overrides(doc, overrides);
    return 0;
  });
  return doc;
}

lsi::Scene load(const std::string& path, const std::vector<std::string>& overrides) {
  const nlohmann::json doc = scene_document(path, overrides);
  return with_path(path, [&] { return lsi::parse_scene(doc); });
}

// The methods of a landslide scene (model/scene_methods.hpp). An MPM run that stops unstable
// still returns what it computed; `mpm_status` then holds the reason (empty when finished or not
// run). `scene_resolved` gets the scene as run (io/resolved_scene.hpp), with the MPM's settings
// as the run used them.
std::vector<lsi::MethodResult> run_scene(const std::string& path, const lsi::Scene& scene,
                                         const std::vector<std::string>& only,
                                         std::string& mpm_status, nlohmann::json& scene_resolved,
                                         std::vector<lsi::MpmSnapshot>* snapshots = nullptr) {
  lsi::SceneRun run =
      with_path(path, [&] { return lsi::run_scene_methods(scene, only, "--methods"); });
  mpm_status = run.mpm_status;
  scene_resolved = lsi::resolved_scene_json(scene, run.mpm_settings ? &*run.mpm_settings : nullptr);
  if (snapshots) *snapshots = std::move(run.snapshots);
  return std::move(run.results);
}

// An MPM verification scene (`mpm_case`): runs it, writes /mpm, prints a summary. Returns the
// exit code: 0 finished, 3 stopped unstable (the histories up to the stop are still written).
int run_mpm_case(const std::string& path, const nlohmann::json& doc, const std::string& out_path,
                 const std::string& format) {
  const lsi::MpmCase c = with_path(path, [&] { return lsi::parse_mpm_case(doc); });
  const lsi::MpmOutcome o = lsi::run_mpm_case(c);
  if (!out_path.empty()) {
    const nlohmann::json resolved = lsi::resolved_mpm_case_json(c);
    if (o.snapshots.empty()) {
      lsi::write_results(out_path, c.source, {o.result}, {}, resolved);
    } else {
      // Both files are written atomically; the XDMF index only after its HDF5 file is in place.
      lsi::write_results(
          out_path, c.source, {o.result},
          [&](long long file_id) { lsi::write_mpm_snapshots(file_id, o.snapshots); }, resolved);
      lsi::write_mpm_snapshots_xdmf(out_path, o.snapshots);
    }
  }
  const auto& res = o.result.series.at("energy_residual").values;
  if (format == "json") {
    nlohmann::json j = {{"status", o.status()},
                        {"finished", o.finished()},
                        {"steps", o.run().steps},
                        {"particles", o.run().particles},
                        {"end_time", o.result.time.empty() ? 0.0 : o.result.time.back()},
                        {"energy_residual", res.empty() ? 0.0 : res.back()},
                        {"solver_seconds", o.run().solver_seconds},
                        {"particle_updates_per_second", o.run().particle_updates_per_second},
                        {"threads", o.run().threads}};
    std::cout << nlohmann::json{{"mpm", j}}.dump(2) << "\n";
  } else {
    std::printf("scene %s (MPM): %s after %lld steps, t = %.4g s; %lld material points\n",
                c.name.c_str(), o.status().c_str(), static_cast<long long>(o.run().steps),
                o.result.time.empty() ? 0.0 : o.result.time.back(),
                static_cast<long long>(o.run().particles));
    std::printf(
        "energy balance residual %.3g; %.3g s in the solver on %d threads, %.3g "
        "particle-updates/s\n",
        res.empty() ? 0.0 : res.back(), o.run().solver_seconds, o.run().threads,
        o.run().particle_updates_per_second);
  }
  if (!o.finished()) {
    std::cerr << "lsi: " << path << ": the MPM run stopped: " << o.status() << "\n";
    return 3;
  }
  return 0;
}

void check_format(const std::string& f) {
  if (f != "table" && f != "json")
    throw lsi::InputError("--format " + f + ": allowed: table, json");
}

}  // namespace

int main(int argc, char** argv) {
#ifdef __linux__
  // OpenMP threads that spin briefly, then sleep (app/openmp_wait_policy.hpp: with the
  // default, unlimited spinning, an MPM run on cores shared with any other work was 10-40 times
  // slower on the 2-core development machine). The OpenMP runtime reads the variables when it
  // loads, before main, so they are set here and the program restarts itself once; a user's own
  // setting (e.g. OMP_WAIT_POLICY=active on a dedicated machine) is kept.
  if (lsi::set_openmp_wait_defaults())
    lsi::restart_program("/proc/self/exe", argv);  // returns only on failure: then run as we are
#endif
  lsi::set_command_line(argc, argv);  // stored in every result file
  CLI::App app{
      "lsi: landslide-structure interaction. Empirical (Di Perna et al. 2022) and "
      "analytical (Cuomo et al. 2022) design methods for barriers hit by flow-like "
      "landslides."};
  app.set_version_flag("--version",
                       std::string("lsi ") + LSI_VERSION + " (" + LSI_GIT_REVISION + ")");
  app.require_subcommand(1);
  std::string progress = "auto";
  app.add_option("--progress", progress,
                 "Progress on standard error: auto (a line rewritten on a terminal, a heartbeat "
                 "line every 30 s in logs), log (the heartbeat), none");
  int runs_at_once = 0;
  app.add_option(
         "--runs-at-once", runs_at_once,
         "MPM runs of one campaign (the cases lsi calibrate runs, an MPM sweep's samples) that "
         "run side by side, one thread each: 0 (default) as many as threads, 1 one after the "
         "other with every thread")
      ->check(CLI::Range(0, 4096));
  long points_per_thread = -1;
  app.add_option("--points-per-thread", points_per_thread,
                 "An MPM run that runs alone (lsi run, design --verify, each run of lsi "
                 "accuracy) with fewer than twice this many material points runs on one thread, "
                 "a larger one on every thread: a small scene runs faster on one. Default 1024 "
                 "for a dry run, 2048 for a saturated one; 0: every run on every thread")
      ->check(CLI::Range(0L, 1000000000L));
  app.fallthrough();  // --progress, --runs-at-once, --points-per-thread also after the subcommand

  std::string scene_path, methods_list, out_path, format = "table";
  std::vector<std::string> overrides;
  const char* set_help =
      "Override one scene value, /json/pointer=value (repeatable; the value is JSON, else a "
      "string), e.g. --set /landslide/velocity_m_s=8; checked as the file is";
  auto* run = app.add_subcommand("run",
                                 "Run a scene: print peak force, rise time, impact "
                                 "duration and final displacement per method");
  run->add_option("scene", scene_path, "Scene JSON file (docs/reference/scene_schema.md)")
      ->required();
  run->add_option("--methods", methods_list,
                  "Comma-separated methods to run (default: the scene's methods block)");
  run->add_option("--out", out_path, "Write time histories and summaries to this HDF5 file");
  run->add_option("--format", format, "Summary format: table or json");
  run->add_option("--set", overrides, set_help)->allow_extra_args(false);

  double max_displacement = 0.5;
  std::string design_scene;
  auto* design = app.add_subcommand("design",
                                    "Inverse design: minimum barrier mass per metre "
                                    "for a tolerable final displacement");
  design->add_option("scene", design_scene, "Scene JSON file")->required();
  design->add_option("--max-displacement", max_displacement, "Tolerable final displacement (m)")
      ->required();
  design->add_option("--methods", methods_list, "empirical and/or analytical");
  design->add_option("--format", format, "table or json");
  design->add_option("--set", overrides, set_help)->allow_extra_args(false);
  bool verify = false;
  design->add_flag("--verify", verify,
                   "Run the MPM (the scene's methods.mpm) on each designed barrier and report its "
                   "displacement and safety beside the tolerance");

  std::vector<std::string> compare_scenes;
  std::string out_dir;
  auto* compare = app.add_subcommand("compare",
                                     "Run several scenes; print the comparison table "
                                     "of the methods and the masses for a tolerable "
                                     "displacement (the reference study)");
  compare->add_option("scenes", compare_scenes, "Scene JSON files")->required();
  compare->add_option("--out-dir", out_dir, "Write one HDF5 file per scene here");
  compare->add_option("--max-displacement", max_displacement,
                      "Tolerable final displacement for the mass column (m)");
  compare->add_option("--format", format, "table or json");
  compare->add_option("--set", overrides, std::string(set_help) + " (in every scene)")
      ->allow_extra_args(false);
  std::string summary_json_path;
  compare->add_option("--summary-json", summary_json_path,
                      "Also write the comparison as JSON to this file (written atomically)");
  std::string verify_design;
  compare->add_option("--verify-design", verify_design,
                      "Comma-separated closed forms (empirical, analytical) whose designed "
                      "barrier the MPM runs, for the column beside the masses");
  std::string convergence_path;
  compare->add_option("--convergence", convergence_path,
                      "A convergence study of these scenes (ci/reference_convergence.py): the MPM "
                      "outputs get its error bars");

  const lsi::Subcommand subcommands[] = {lsi::add_sweep_command(app), lsi::add_merge_command(app),
                                         lsi::add_calibrate_command(app),
                                         lsi::add_accuracy_command(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    lsi::reject_empty_values(app);
    lsi::set_progress_mode(lsi::progress_mode_from(progress));
    lsi::set_runs_at_once(runs_at_once);
    if (points_per_thread >= 0) lsi::set_points_per_thread(points_per_thread);
    for (const auto& s : subcommands)
      if (*s.command) return s.run();
    check_format(format);
    const auto only = parse_methods(methods_list);
    if (*run) {
      if (!out_path.empty()) {
        lsi::check_output_file("--out", out_path, {scene_path});
        lsi::check_output_file("--out", lsi::mpm_snapshots_xdmf_path(out_path), {scene_path});
      }
      const nlohmann::json doc = scene_document(scene_path, overrides);
      if (lsi::is_mpm_case(doc)) return run_mpm_case(scene_path, doc, out_path, format);
      const lsi::Scene scene = with_path(scene_path, [&] { return lsi::parse_scene(doc); });
      std::string mpm_status;
      nlohmann::json resolved;
      std::vector<lsi::MpmSnapshot> snapshots;
      const auto results = run_scene(scene_path, scene, only, mpm_status, resolved, &snapshots);
      if (!out_path.empty()) {
        if (snapshots.empty()) {
          lsi::write_results(out_path, scene.source, results, {}, resolved);
        } else {  // as for verification scenes: the XDMF index after its HDF5 file
          lsi::write_results(
              out_path, scene.source, results,
              [&](long long file_id) { lsi::write_mpm_snapshots(file_id, snapshots); }, resolved);
          lsi::write_mpm_snapshots_xdmf(out_path, snapshots);
        }
      }
      if (format == "json")
        std::cout << lsi::summary_json(results).dump(2) << "\n";
      else
        std::cout << lsi::summary_table(scene, results);
      if (!mpm_status.empty()) {
        std::cerr << "lsi: " << scene_path << ": the MPM run stopped: " << mpm_status << "\n";
        return 3;
      }
    } else if (*design) {
      const lsi::Scene scene = load(design_scene, overrides);
      const auto designs = lsi::design_barrier_mass(scene, max_displacement, only);
      const auto checks =
          verify ? with_path(design_scene,
                             [&] { return lsi::verify_designs(scene, designs, max_displacement); })
                 : std::vector<lsi::DesignCheck>{};
      if (format == "json")
        std::cout << lsi::design_json(designs, max_displacement, checks).dump(2) << "\n";
      else
        std::cout << lsi::design_table(scene, designs, max_displacement, checks);
    } else if (*compare) {
      std::vector<lsi::ComparisonRow> rows;
      bool unstable = false;
      std::optional<lsi::ConvergenceStudy> convergence;
      if (!convergence_path.empty()) convergence = lsi::load_convergence_study(convergence_path);
      // Every input is read and every output checked before the first run: two scenes of one
      // name would write one file, a name with a path in it would write outside --out-dir.
      std::vector<std::string> inputs = compare_scenes;
      if (!convergence_path.empty()) inputs.push_back(convergence_path);
      if (!summary_json_path.empty())
        lsi::check_output_file("--summary-json", summary_json_path, inputs);
      std::vector<lsi::Scene> scenes;
      std::map<std::string, std::string> file_of_name;
      for (const auto& path : compare_scenes) {
        scenes.push_back(load(path, overrides));
        const std::string& name = scenes.back().name;
        if (!out_dir.empty()) {
          lsi::check_file_name(path + ": name", name);
          const auto [it, fresh] = file_of_name.emplace(name, path);
          if (!fresh)
            throw lsi::InputError(path + ": name = \"" + name + "\": also the name of " +
                                  it->second + " (--out-dir writes one file per name)");
          lsi::check_output_file(
              "--out-dir", (std::filesystem::path(out_dir) / (name + ".h5")).string(), inputs);
        }
      }
      if (!out_dir.empty()) lsi::check_output_directory("--out-dir", out_dir);
      std::vector<std::string> checked_methods;
      for (const auto& m : parse_methods(verify_design)) {
        if (m != "empirical" && m != "analytical")
          throw lsi::InputError("--verify-design " + m + ": allowed: empirical, analytical");
        checked_methods.push_back(m);
      }
      // What the checks need, before any run.
      const std::size_t n = compare_scenes.size();
      rows.resize(n);
      for (std::size_t k = 0; k < n; ++k) {
        rows[k].scene = scenes[k].name;
        if (!scenes[k].barrier.fixed && !checked_methods.empty())  // refuses no methods.mpm
          with_path(compare_scenes[k], [&] {
            return lsi::verify_designs(scenes[k], {}, max_displacement, checked_methods);
          });
      }
      // Where an MPM runs, the work goes side by side (model/concurrent_runs.hpp:
      // --runs-at-once): the designs' masses (closed forms, a search each), then every scene's
      // methods and the MPM of each design checked, each scene's file written as its run ends.
      // The closed forms alone run one after the other, without Kokkos.
      const bool mpm = std::any_of(scenes.begin(), scenes.end(), [&](const lsi::Scene& s) {
        return lsi::scene_runs_mpm(s, only) || (!checked_methods.empty() && !s.barrier.fixed);
      });
      const auto each = [&](std::size_t tasks, const std::function<void(std::size_t)>& task,
                            const std::string& label, int runs = 0) {
        if (mpm) return lsi::run_concurrently(tasks, task, runs, label);
        for (std::size_t k = 0; k < tasks; ++k) task(k);
      };
      each(
          n,
          [&](std::size_t k) {
            if (!scenes[k].barrier.fixed)
              rows[k].designs = lsi::design_barrier_mass(scenes[k], max_displacement, only);
          },
          "compare, the mass searches");
      struct Check {
        std::size_t scene, design;
        std::vector<lsi::DesignCheck> result;  // none, or the design's check
      };
      std::vector<Check> checks;
      for (std::size_t k = 0; k < n && !checked_methods.empty(); ++k)
        for (std::size_t d = 0; d < rows[k].designs.size(); ++d)
          if (lsi::design_checked(rows[k].designs[d], checked_methods))
            checks.push_back({k, d, {}});
      std::vector<std::string> mpm_status(n), no_error_bars(n);
      std::mutex files;  // HDF5 calls one at a time
      const auto run_task = [&](std::size_t task) {
        if (task >= n) {
          Check& c = checks[task - n];
          const lsi::Scene& scene = scenes[c.scene];
          c.result = with_path(compare_scenes[c.scene], [&] {
            return lsi::verify_designs(scene, {rows[c.scene].designs[c.design]}, max_displacement,
                                       checked_methods);
          });
          return;
        }
        nlohmann::json resolved;
        rows[task].results =
            run_scene(compare_scenes[task], scenes[task], only, mpm_status[task], resolved);
        for (auto& r : rows[task].results)
          if (convergence && r.method == "mpm")
            no_error_bars[task] = lsi::attach_convergence(*convergence, scenes[task], r);
        if (!out_dir.empty()) {
          const auto file = std::filesystem::path(out_dir) / (scenes[task].name + ".h5");
          const std::lock_guard<std::mutex> lock(files);
          lsi::write_results(file.string(), scenes[task].source, rows[task].results, {}, resolved);
        }
      };
      // The MPM runs: as many at once as fit in the memory (model/mpm_footprint.hpp).
      std::vector<const lsi::Scene*> mpm_scenes;
      for (const auto& s : scenes) mpm_scenes.push_back(&s);
      const int runs = mpm ? lsi::campaign_runs_that_fit(n + checks.size(), mpm_scenes) : 1;
      each(n + checks.size(), run_task, "compare", runs);
      for (Check& c : checks)
        for (auto& r : c.result) rows[c.scene].checks.push_back(std::move(r));
      for (std::size_t k = 0; k < n; ++k) {
        const std::string& path = compare_scenes[k];
        if (!mpm_status[k].empty()) {
          std::cerr << "lsi: " << path << ": the MPM run stopped: " << mpm_status[k] << "\n";
          unstable = true;
        }
        if (!no_error_bars[k].empty())
          std::cerr << "lsi: " << path << ": no error bars from " << convergence_path << ": "
                    << no_error_bars[k] << "\n";
      }
      if (format == "json")
        std::cout << lsi::comparison_json(rows, max_displacement).dump(2) << "\n";
      else
        std::cout << lsi::comparison_table(rows, max_displacement);
      if (!summary_json_path.empty()) {
        lsi::write_text_atomically(summary_json_path,
                                   lsi::comparison_json(rows, max_displacement).dump(2) + "\n");
      }
      if (unstable) return 3;
    }
  } catch (const lsi::InputError& e) {
    std::cerr << "lsi: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lsi: failed: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
