// The accuracy study (`lsi accuracy`, issue 6): error against run time for the MPM and the closed
// forms. A study file names a base impact scene and series of MPM runs that refine one
// discretisation parameter (cells per landslide thickness, points per cell, Courant number), each
// series with its own settings (e.g. dry PIC, dry APIC, saturated explicit or semi-implicit drag).
// Every run records its outputs and wall time; every series gets the observed order, Richardson
// extrapolation and GCI of each output (sweeps/grid_convergence.hpp); one series is the reference:
// its extrapolated (or finest) values are what every run and the closed forms are measured against.
// Schema: docs/reference/scene_schema.md, "Accuracy studies"; method and results: docs/vv/accuracy.md.
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/method_result.hpp"
#include "sweeps/grid_convergence.hpp"

namespace lsi {

// The outputs an accuracy study can follow (MethodResult scalars, plus the largest |energy
// residual| of the run, whose exact value is 0).
const std::vector<std::string>& accuracy_output_names();

struct AccuracySeries {
  std::string name;
  std::string parameter;       // "cells_per_thickness", "particles_per_cell" or "courant"
  std::vector<double> values;  // as given; runs go coarse to fine
  nlohmann::json set;          // JSON pointer -> value, applied to the base scene
  bool reference = false;
  // Errors of this series' runs are against the best values of this series (by name; itself for
  // self-convergence) instead of the study's reference series, e.g. saturated runs against the
  // best saturated estimate rather than the dry reference.
  std::string compare_to;
  std::vector<std::string> outputs;
};

struct AccuracyStudy {
  std::string name;
  nlohmann::json scene_document;  // the base scene
  std::vector<std::string> outputs;
  std::vector<AccuracySeries> series;
  nlohmann::json source;  // the study as given, scene inlined
};

// Throws InputError naming the key, its value and what is allowed.
AccuracyStudy parse_accuracy_study(const nlohmann::json& j, const std::string& base_dir);
// The series' name as the start of its run files' names: letters and digits in lower case, every
// other run of characters one '-' ("Cell size / Courant" -> "cell-size-courant"). The parser
// refuses two series whose names give the same stem.
std::string series_file_stem(const std::string& name);
AccuracyStudy load_accuracy_study(const std::string& path);

// The spacing h that the error is assumed to scale with, for one value of a series' parameter.
double accuracy_spacing(const std::string& parameter, double value);

// The scene of one run: the base scene with the series' settings and its parameter's value.
nlohmann::json accuracy_run_scene(const AccuracyStudy& study, const AccuracySeries& series,
                                  double value);

struct AccuracyRun {
  double value = 0.0, h = 0.0;
  std::string status;  // "finished" or why the run stopped
  bool finished = false;
  double solver_seconds = 0.0;  // the solver loop (no setup, no I/O)
  double steps = 0.0, particles = 0.0;
  int threads = 0;  // host threads the run's kernels ran on (model/run_threads.hpp; 0: a device)
  std::map<std::string, double> outputs;  // NaN: not known (e.g. a run cut short)
  MethodResult result;                    // the histories (not kept in the run's JSON record)
};

// Runs the MPM scene in-process. Throws InputError for an invalid scene.
AccuracyRun run_accuracy_case(const nlohmann::json& scene, const AccuracySeries& series,
                              double value);

nlohmann::json to_json(const AccuracyRun& r);
AccuracyRun accuracy_run_from_json(const nlohmann::json& j);

// Convergence of one output over the finished runs of a series (ordered by h, finest first):
// the finest triple's analysis, and the order of the next-coarser triple when there are 4 runs.
struct OutputConvergence {
  int runs = 0;                    // finished runs with a finite value
  sweeps::GridConvergence finest;  // valid when runs >= 3
  double order_next = 0.0;         // NaN unless runs >= 4
  // Outputs with a known exact value (the energy residual, exactly 0): the order of the error
  // itself, ln(e2/e1) / ln(h2/h1), over the two finest runs and over the next pair (NaN if fewer).
  bool exact = false;
  double order_to_exact = 0.0, order_to_exact_next = 0.0;
  double best = 0.0;        // extrapolated when monotonic, else the finest value
  std::string best_source;  // "richardson", "finest run", "exact"
};
OutputConvergence output_convergence(const std::vector<AccuracyRun>& runs,
                                     const std::string& output);

// Signed error of a value against a reference: relative when the reference is not zero (and the
// output has no exact zero), absolute otherwise; NaN when either is not finite.
double accuracy_error(const std::string& output, double value, double reference);

// A closed-form method evaluated on the base scene, and its wall time per evaluation.
struct ClosedFormTiming {
  std::string method;  // "empirical", "analytical"
  double seconds_per_evaluation = 0.0;
  std::map<std::string, double> outputs;
};
std::vector<ClosedFormTiming> time_closed_forms(const AccuracyStudy& study);

// Everything the study found, as JSON (results/accuracy/accuracy.json): the study, the machine,
// every run with its errors against the reference, each series' convergence per output, the
// reference values, and the closed forms with their errors. `runs[i]` belongs to `study.series[i]`.
nlohmann::json accuracy_report(const AccuracyStudy& study,
                               const std::vector<std::vector<AccuracyRun>>& runs,
                               const std::vector<ClosedFormTiming>& closed_forms);
// The same as Markdown tables (results/accuracy/accuracy.md).
std::string accuracy_markdown(const nlohmann::json& report);

}  // namespace lsi
