// `lsi sweep STUDY --out FILE` and `lsi merge --out FILE SHARDS...`: run a study file (Monte
// Carlo, Latin hypercube, Sobol, grid or given points) and join the files of a sharded run.
#include <iostream>

#include "io/output_paths.hpp"
#include "io/sweep_csv.hpp"
#include "io/sweep_file.hpp"
#include "model/study.hpp"
#include "app/subcommand.hpp"
#include "app/sweep_runner.hpp"
#include "app/sweep_report.hpp"
#include "io/study_parser.hpp"

namespace lsi {
namespace {

int report(const SweepOutcome& o, const std::string& out, const std::string& format) {
  if (format == "json")
    std::cout << sweep_outcome_json(o, out).dump(2) << "\n";
  else
    std::cout << sweep_outcome_text(o, out);
  return 0;
}

void check_format(const std::string& f) {
  if (f != "table" && f != "json") throw InputError("--format " + f + ": allowed: table, json");
}

}  // namespace

Subcommand add_sweep_command(CLI::App& app) {
  struct Args {
    std::string study, out, table_csv, shard = "0/1", format = "table";
    bool resume = false;
  };
  auto args = std::make_shared<Args>();
  Subcommand s;
  s.command = app.add_subcommand(
      "sweep",
      "Run a study file (docs/reference/scene_schema.md, \"Study files\"): Monte Carlo, Latin "
      "hypercube, Sobol, grid or given points of a scene through the methods; per-sample table "
      "and statistics in HDF5");
  s.command->add_option("study", args->study, "Study JSON file")->required();
  s.command
      ->add_option("--out", args->out,
                   "HDF5 result file (chunks go to <out>.parts until "
                   "the sweep is complete)")
      ->required();
  CLI::Option* table_csv =
      s.command->add_option("--table-csv", args->table_csv,
                            "Also write the per-sample table (index, inputs, outputs, status; in "
                            "sample order) to this CSV file");
  s.command->add_flag("--resume", args->resume, "Continue an interrupted run of the same study");
  s.command->add_option("--shard", args->shard,
                        "Run only shard i of N (i/N); join the shards "
                        "with `lsi merge`");
  s.command->add_option("--format", args->format, "Summary format: table or json");
  s.run = [args, table_csv] {
    check_format(args->format);
    SweepOptions o;
    o.out = args->out;
    o.resume = args->resume;
    parse_shard(args->shard, o.shard, o.shard_count);
    check_output_file("--out", args->out, {args->study});
    const bool csv = table_csv->count() > 0;
    if (csv) check_output_file("--table-csv", args->table_csv, {args->study, args->out});
    const Study study = load_study(args->study);
    if (!study.points.file.empty()) {  // a given points file is an input too
      check_output_file("--out", args->out, {study.points.file});
      if (csv) check_output_file("--table-csv", args->table_csv, {study.points.file});
    }
    const SweepOutcome outcome = run_sweep(study, o);
    if (csv) write_sweep_table_csv(args->table_csv, read_sweep_file(o.out).table);
    return report(outcome, o.out, args->format);
  };
  return s;
}

Subcommand add_merge_command(CLI::App& app) {
  struct Args {
    std::vector<std::string> shards;
    std::string out, format = "table";
  };
  auto args = std::make_shared<Args>();
  Subcommand s;
  s.command = app.add_subcommand("merge",
                                 "Join the result files of a sharded sweep into the "
                                 "file an unsharded run writes");
  s.command->add_option("shards", args->shards, "Shard result files (lsi sweep --shard i/N)")
      ->required();
  s.command->add_option("--out", args->out, "Merged HDF5 file")->required();
  s.command->add_option("--format", args->format, "Summary format: table or json");
  s.run = [args] {
    check_format(args->format);
    check_output_file("--out", args->out, args->shards);
    return report(merge_sweeps(args->shards, args->out), args->out, args->format);
  };
  return s;
}

}  // namespace lsi
