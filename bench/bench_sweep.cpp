// Throughput of the closed-form part of `lsi sweep` on the study scenes/studies/L1-B1-monte-carlo.json
// (5 inputs: lognormal, truncated normal x2 with one correlated pair, discrete, uniform), batch 2^20
// samples, on the default execution space (OpenMP: set OMP_NUM_THREADS):
//   BM_sampler                 the sampler alone (sample_batch, sweeps/sampler.hpp)
//   BM_sweep_kernel/methods:M  the sweep kernel (evaluate_closed_form_chunk, sweeps/closed_form_sweep.hpp):
//                              draw, check the scene, evaluate; M = 1 empirical, 2 analytical, 3 both
//   BM_models_only/methods:M   the models alone (kernels/closed_form/batch.hpp) on the same samples'
//                              model inputs, precomputed
//   BM_sweep_overhead/methods:M  the overhead of the sweep machinery: time = sweep kernel - models
//                              only, both timed in the same iteration on the same samples; counter
//                              overhead_ns_per_sample (sampling + scene check + the per-sample copies)
//   BM_chunk_write / BM_chunk_read  write_sweep_file / read_sweep_file (model/sweep_table.hpp) of a
//                              2^20-row table (5 inputs, 4 output columns) in /tmp, fsync included,
//                              stored plain as the runner stores its chunks (io/sweep_file.hpp)
//   BM_table_stream            the same table written as `lsi sweep` writes its result file
//                              (io/sweep_table_stream.hpp): its chunks compressed on the threads
//                              (io/compressed_chunks.hpp) and written, then the file finished;
//                              counter stored_fraction = the file's bytes / the table's
//   BM_column_accumulator / BM_describe  one output column's statistics (2^23 values, one thread)
//                              as `lsi sweep` takes them, a chunk at a time, and as `lsi merge`
//                              does, from the gathered column; counter kept_fraction = the
//                              values the accumulator keeps / the column's
// items_per_second = samples per second; per-sample cost = 1 / items_per_second.
// Run (docs/notes/performance.md, "Sweeps", has the numbers and the machine):
//   OMP_NUM_THREADS=2 OMP_PROC_BIND=false OMP_WAIT_POLICY=passive build/bench/bench_sweep
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <Kokkos_Core.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "model/study.hpp"
#include "model/sweep_table.hpp"
#include "kernels/closed_form/batch.hpp"
#include "sweeps/closed_form_sweep.hpp"
#include "sweeps/column_accumulator.hpp"
#include "sweeps/statistics.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time
#include "io/study_parser.hpp"
#include "io/sweep_file.hpp"
#include "io/sweep_table_stream.hpp"

namespace {
using namespace lsi;
using Exec = Kokkos::DefaultExecutionSpace;
using Mem = Exec::memory_space;
using Matrix = Kokkos::View<double**, Kokkos::LayoutLeft, Mem>;
constexpr std::uint64_t kBatch = std::uint64_t{1} << 20;

const Study& study() {
  // Never destroyed: what holds Views must not outlive Kokkos::finalize. Moved from a named
  // Study: nvcc 13.0's device front end aborts ("Compilation aborted.", no message) on
  // `new Study(load_study(...))`, a new-expression initialised from a prvalue.
  static const Study* s = [] {
    Study loaded = load_study(LSI_SOURCE_DIR "/scenes/studies/L1-B1-monte-carlo.json");
    return new Study(std::move(loaded));
  }();
  return *s;
}

sweeps::ClosedFormSweep<Mem> sweep_of(const Study& s, int methods) {
  sweeps::ClosedFormSweep<Mem> sweep(s.sampler<Mem>());
  sweep.base = s.base_values;
  for (std::size_t d = 0; d < s.inputs.size(); ++d) sweep.target[d] = s.inputs[d].field;
  sweep.empirical = (methods & 1) != 0;
  sweep.analytical = (methods & 2) != 0;
  return sweep;
}

const char* methods_label(int m) { return m == 1 ? "empirical" : m == 2 ? "analytical" : "both"; }

// The chunk buffers of the sweep kernel (as app/sweep_runner.cpp allocates them).
struct Chunk {
  Matrix inputs, outputs;
  Kokkos::View<int*, Mem> invalid;
  sweeps::ClosedFormChunkColumns<Mem> columns;  // kept from call to call, as the sweep does
  explicit Chunk(int dims)
      : inputs("inputs", kBatch, dims),
        outputs("outputs", kBatch, 2 * sweeps::closed_form_output_count),
        invalid("invalid", kBatch) {}
};

// The model inputs of the first kBatch samples of the study (what the sweep kernel derives from
// each sample's scene values), for the models-only kernels.
struct ModelBatch {
  Kokkos::View<double* [10], Kokkos::LayoutLeft, Mem> data;
  ClosedFormInputs<Mem> in_empirical, in_analytical;
  ClosedFormOutputs<Mem> out_empirical, out_analytical;
  EmpiricalCoefficients empirical;
  ModelBatch() : data("model inputs", kBatch) {
    const Study& s = study();
    const auto sweep = sweep_of(s, 3);
    const int dims = sweep.sampler.dimensions();
    Chunk c(dims);
    sweeps::evaluate_closed_form_chunk(Exec(), sweep, 0, c.inputs, c.outputs, c.invalid, c.columns);
    Exec().fence();
    const auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.inputs);
    Kokkos::View<double* [10], Kokkos::LayoutLeft, Kokkos::HostSpace> h("host", kBatch);
    // tau_e and tau_a/lambda as the sweep uses them (column 8 = empirical tau here; the analytical
    // batch gets its own tau/lambda columns through a second view below).
    for (std::uint64_t i = 0; i < kBatch; ++i) {
      sweeps::SceneValues v = sweep.base;
      for (int d = 0; d < dims; ++d)
        if (sweep.target[d] >= 0) v.value[sweep.target[d]] = x(i, d);
      const sweeps::ModelInputs m = sweeps::model_inputs(v);
      h(i, 0) = v.value[sweeps::thickness_m];
      h(i, 1) = v.value[sweeps::velocity_m_s];
      h(i, 2) = v.value[sweeps::density_kg_m3];
      h(i, 3) = m.landslide_mass;
      h(i, 4) = m.equivalent_length;
      h(i, 5) = m.barrier_mass;
      h(i, 6) = v.value[sweeps::base_friction];
      h(i, 7) = m.face_angle_rad;
      h(i, 8) = v.value[sweeps::empirical_tau];
      TwoBodyCoefficients tc = default_two_body_coefficients(v.fixed);
      if (v.analytical_lambda_given) tc.lambda = v.value[sweeps::analytical_lambda];
      h(i, 9) = tc.lambda;
      analytical_tau = v.analytical_tau_given ? v.value[sweeps::analytical_tau] : tc.tau;
      empirical.a1 = v.value[sweeps::empirical_a1];
      empirical.a2 = v.value[sweeps::empirical_a2];
      empirical.kappa = v.value[sweeps::empirical_kappa];
    }
    Kokkos::deep_copy(data, h);
    tau_a = Kokkos::View<double*, Mem>("analytical tau", kBatch);
    Kokkos::deep_copy(tau_a, analytical_tau);
    auto col = [&](int k) { return Kokkos::subview(data, Kokkos::ALL, k); };
    in_empirical = {col(0), col(1), col(2), col(3), col(4), col(5), col(6), col(7), col(8), col(9)};
    in_analytical = {col(0), col(1), col(2), col(3), col(4), col(5), col(6), col(7), tau_a, col(9)};
    auto outs = [](const char* p) {
      return ClosedFormOutputs<Mem>{Kokkos::View<double*, Mem>(std::string(p) + " peak", kBatch),
                                    Kokkos::View<double*, Mem>(std::string(p) + " t1", kBatch),
                                    Kokkos::View<double*, Mem>(std::string(p) + " t2", kBatch),
                                    Kokkos::View<double*, Mem>(std::string(p) + " dx", kBatch)};
    };
    out_empirical = outs("empirical");
    out_analytical = outs("analytical");
  }
  void run(int methods) const {
    if (methods & 1) evaluate_empirical_batch(Exec(), in_empirical, empirical, out_empirical);
    if (methods & 2) evaluate_two_body_batch(Exec(), in_analytical, out_analytical);
  }
  double analytical_tau = 0.25;
  Kokkos::View<double*, Mem> tau_a;
};

const ModelBatch& model_batch() {
  static const ModelBatch* b = new ModelBatch;  // never destroyed (holds Views)
  return *b;
}

void BM_sampler(benchmark::State& state) {
  const auto sampler = study().sampler<Mem>();
  Matrix out("samples", kBatch, sampler.dimensions());
  sweeps::sample_batch(Exec(), sampler, 0, out);  // warm-up: first touch of the pages
  Exec().fence();
  for (auto _ : state) {
    sweeps::sample_batch(Exec(), sampler, 0, out);
    Exec().fence();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.counters["threads"] = Exec().concurrency();
}
BENCHMARK(BM_sampler)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_sweep_kernel(benchmark::State& state) {
  const int methods = static_cast<int>(state.range(0));
  const auto sweep = sweep_of(study(), methods);
  Chunk c(sweep.sampler.dimensions());
  sweeps::evaluate_closed_form_chunk(Exec(), sweep, 0, c.inputs, c.outputs, c.invalid, c.columns);
  Exec().fence();
  for (auto _ : state) {
    sweeps::evaluate_closed_form_chunk(Exec(), sweep, 0, c.inputs, c.outputs, c.invalid, c.columns);
    Exec().fence();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetLabel(methods_label(methods));
  state.counters["threads"] = Exec().concurrency();
}
BENCHMARK(BM_sweep_kernel)
    ->ArgName("methods")
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_models_only(benchmark::State& state) {
  const int methods = static_cast<int>(state.range(0));
  const ModelBatch& b = model_batch();
  b.run(methods);
  Exec().fence();
  for (auto _ : state) {
    b.run(methods);
    Exec().fence();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetLabel(methods_label(methods));
  state.counters["threads"] = Exec().concurrency();
}
BENCHMARK(BM_models_only)
    ->ArgName("methods")
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_sweep_overhead(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const int methods = static_cast<int>(state.range(0));
  const auto sweep = sweep_of(study(), methods);
  const ModelBatch& b = model_batch();
  Chunk c(sweep.sampler.dimensions());
  sweeps::evaluate_closed_form_chunk(Exec(), sweep, 0, c.inputs, c.outputs, c.invalid, c.columns);
  b.run(methods);
  Exec().fence();
  double kernel_s = 0, models_s = 0;
  for (auto _ : state) {
    auto t0 = Clock::now();
    sweeps::evaluate_closed_form_chunk(Exec(), sweep, 0, c.inputs, c.outputs, c.invalid, c.columns);
    Exec().fence();
    auto t1 = Clock::now();
    b.run(methods);
    Exec().fence();
    auto t2 = Clock::now();
    const double k = std::chrono::duration<double>(t1 - t0).count();
    const double m = std::chrono::duration<double>(t2 - t1).count();
    kernel_s += k;
    models_s += m;
    state.SetIterationTime(k - m > 0 ? k - m : 0.0);
  }
  const double per = 1e9 / static_cast<double>(state.iterations() * kBatch);
  state.counters["kernel_ns_per_sample"] = kernel_s * per;
  state.counters["models_ns_per_sample"] = models_s * per;
  state.counters["overhead_ns_per_sample"] = (kernel_s - models_s) * per;
  state.SetLabel(methods_label(methods));
}
BENCHMARK(BM_sweep_overhead)
    ->ArgName("methods")
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// A chunk of kBatch rows as the sweep writes it: 5 inputs, the study's 4 output columns, all
// samples ok.
SweepTable chunk_table() {
  const Study& s = study();
  std::vector<std::string> paths;
  for (const auto& in : s.inputs) paths.push_back(in.path);
  SweepTable t = SweepTable::with_columns(paths, s.output_columns());
  const auto sweep = sweep_of(s, 3);
  Chunk c(sweep.sampler.dimensions());
  sweeps::evaluate_closed_form_chunk(Exec(), sweep, 0, c.inputs, c.outputs, c.invalid, c.columns);
  Exec().fence();
  const auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.inputs);
  const auto y = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.outputs);
  t.index.resize(kBatch);
  t.status.assign(kBatch, 0);
  t.wall_time.assign(kBatch, 1e-7f);
  for (std::uint64_t i = 0; i < kBatch; ++i) t.index[i] = i;
  for (std::size_t d = 0; d < paths.size(); ++d) {
    t.inputs[d].resize(kBatch);
    for (std::uint64_t i = 0; i < kBatch; ++i) t.inputs[d][i] = x(i, d);
  }
  // The study's output columns ("<method>/<output>", methods outermost), each from its column of
  // the kernel's outputs (the empirical model's first), as app/sweep_runner.cpp copies them.
  std::size_t k = 0;
  for (const auto& m : s.methods)
    for (const auto& o : s.outputs) {
      int out = 0;
      while (sweeps::closed_form_output_name[out] != o) ++out;
      const int column = (m == "analytical" ? sweeps::closed_form_output_count : 0) + out;
      t.outputs[k].resize(kBatch);
      for (std::uint64_t i = 0; i < kBatch; ++i) t.outputs[k][i] = y(i, column);
      ++k;
    }
  return t;
}

// The bytes of a table's rows as the file stores them: index 8, status 1, wall time 4, and 8 per
// input and output value.
double table_bytes(const SweepTable& t) {
  return double(t.rows() * (8 + 1 + 4 + 8 * (t.inputs.size() + t.outputs.size())));
}

std::string chunk_path() {
  return "/tmp/lsi_bench_sweep_chunk." + std::to_string(::getpid()) + ".h5";
}

SweepHeader chunk_header() {
  const Study& s = study();
  SweepHeader h;
  h.study = s.source;
  h.fingerprint = s.fingerprint;
  h.planned_samples = s.samples;
  h.chunk_samples = kBatch;
  h.complete = true;
  return h;
}

void BM_chunk_write(benchmark::State& state) {
  const SweepTable t = chunk_table();
  const SweepHeader h = chunk_header();
  const std::string path = chunk_path();
  for (auto _ : state) write_sweep_file(path, h, t, nullptr, SweepStorage::Plain);
  std::remove(path.c_str());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetBytesProcessed(static_cast<std::int64_t>(double(state.iterations()) * table_bytes(t)));
}
BENCHMARK(BM_chunk_write)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_chunk_read(benchmark::State& state) {
  const std::string path = chunk_path();
  const SweepTable t = chunk_table();
  write_sweep_file(path, chunk_header(), t, nullptr, SweepStorage::Plain);
  for (auto _ : state) {
    SweepFile f = read_sweep_file(path);
    benchmark::DoNotOptimize(f.table.index.data());
  }
  std::remove(path.c_str());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetBytesProcessed(static_cast<std::int64_t>(double(state.iterations()) * table_bytes(t)));
}
BENCHMARK(BM_chunk_read)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_table_stream(benchmark::State& state) {
  const SweepTable t = chunk_table();
  const SweepHeader h = chunk_header();
  const std::string path = chunk_path();
  const std::uint64_t chunk_rows =
      SweepTableStream::chunk_rows_for(t.inputs.size(), kBatch, kBatch);
  for (auto _ : state) {
    SweepTableStream stream(path, t.input_paths, t.output_columns, kBatch, chunk_rows);
    stream.append(t);
    stream.finish(h, {}, {}, nullptr);
  }
  state.counters["stored_fraction"] = double(std::filesystem::file_size(path)) / table_bytes(t);
  std::remove(path.c_str());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetBytesProcessed(static_cast<std::int64_t>(double(state.iterations()) * table_bytes(t)));
}
BENCHMARK(BM_table_stream)->Unit(benchmark::kMillisecond)->UseRealTime();

// The statistics of one output column, the analytical model's peak force of the 2^20-row chunk
// fed 8 times (2^23 values), on one thread: BM_column_accumulator hands it over a chunk at a
// time to a ColumnAccumulator and describes it at the end (sweeps/column_accumulator.hpp), as
// `lsi sweep` does; BM_describe describes the gathered column (sweeps/statistics.hpp), as
// `lsi merge` does. items_per_second = values per second.
const std::vector<double>& peak_force_column() {
  static const std::vector<double> column = [] {
    const SweepTable t = chunk_table();
    std::size_t c = 0;
    while (c + 1 < t.output_columns.size() && t.output_columns[c] != "analytical/peak_force") ++c;
    return t.outputs[c];
  }();
  return column;
}
constexpr int kColumnFeeds = 8;

void BM_column_accumulator(benchmark::State& state) {
  const std::vector<double>& v = peak_force_column();
  const Study& s = study();
  double q50 = 0.0;
  for (auto _ : state) {
    sweeps::ColumnAccumulator a({2.0e5}, s.confidence);
    for (int k = 0; k < kColumnFeeds; ++k) a.add(v.data(), v.size());
    sweeps::OrderScratch scratch;
    q50 = a.describe([&] { return std::vector<double>(); }, scratch).q50;
    state.counters["kept_fraction"] =
        double(a.values_kept()) / (double(kColumnFeeds) * double(v.size()));
  }
  benchmark::DoNotOptimize(q50);
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kColumnFeeds * std::int64_t(v.size()));
}
BENCHMARK(BM_column_accumulator)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_describe(benchmark::State& state) {
  const std::vector<double>& v = peak_force_column();
  const Study& s = study();
  double q50 = 0.0;
  for (auto _ : state) {
    std::vector<double> all;
    all.reserve(kColumnFeeds * v.size());
    for (int k = 0; k < kColumnFeeds; ++k) all.insert(all.end(), v.begin(), v.end());
    sweeps::OrderScratch scratch;
    q50 = sweeps::describe(all, scratch, s.confidence).q50;
    sweeps::ExceedanceEstimate e = sweeps::exceedance(all, 2.0e5, s.confidence);
    benchmark::DoNotOptimize(e);
  }
  benchmark::DoNotOptimize(q50);
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kColumnFeeds * std::int64_t(v.size()));
}
BENCHMARK(BM_describe)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("kokkos_version", std::to_string(KOKKOS_VERSION));
  benchmark::AddCustomContext("git_revision", LSI_GIT_REVISION);
  benchmark::AddCustomContext("execution_space", Exec::name());
  benchmark::AddCustomContext("concurrency", std::to_string(Exec().concurrency()));
  benchmark::AddCustomContext("batch", std::to_string(kBatch));
  benchmark::AddCustomContext("study", "scenes/studies/L1-B1-monte-carlo.json");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
