// A Kokkos tools library that times each kernel (parallel_for, _reduce, _scan) and the host gap
// before it, keyed by the kernel before and after, and prints both tables (largest total first)
// and a histogram of the gaps to stderr when Kokkos finalizes. For a program on one host
// thread's kernels at a time (the gaps of concurrent runs would interleave). Not part of the
// build; with the Kokkos of the build:
//   g++ -O2 -shared -fPIC -o kernel_gaps.so tools/kernel_gaps.cpp
//   KOKKOS_PROFILE_LIBRARY=$PWD/kernel_gaps.so lsi --progress none run SCENE --out X.h5
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {
using Clock = std::chrono::steady_clock;
struct Total {
  long calls = 0;
  double seconds = 0.0;
};
std::map<std::string, Total> kernels, gaps;
std::string previous = "(start)", current;
Clock::time_point began, ended;
bool any_ended = false;
constexpr int kBins = 6;
const char* const kBinNames[kBins] = {"< 1 us",   "1-3 us",    "3-10 us",
                                      "10-30 us", "30-100 us", "> 100 us"};
const double kBinEdges[kBins - 1] = {1e-6, 3e-6, 1e-5, 3e-5, 1e-4};
Total bins[kBins];

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

void begin(const char* name) {
  const Clock::time_point now = Clock::now();
  if (any_ended) {
    const double gap = seconds(now - ended);
    Total& g = gaps[previous + " -> " + name];
    ++g.calls;
    g.seconds += gap;
    const int bin =
        static_cast<int>(std::upper_bound(kBinEdges, kBinEdges + kBins - 1, gap) - kBinEdges);
    ++bins[bin].calls;
    bins[bin].seconds += gap;
  }
  current = name;
  began = now;
}

void end() {
  ended = Clock::now();
  Total& k = kernels[current];
  ++k.calls;
  k.seconds += seconds(ended - began);
  previous = current;
  any_ended = true;
}

void print(const char* title, const std::map<std::string, Total>& table, const int rows) {
  std::vector<std::pair<std::string, Total>> sorted(table.begin(), table.end());
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  double sum = 0.0;
  for (const auto& entry : sorted) sum += entry.second.seconds;
  std::fprintf(stderr, "== %s: %.4f s\n", title, sum);
  for (int r = 0; r < static_cast<int>(sorted.size()) && r < rows; ++r)
    std::fprintf(stderr, "%9.4f s %9ld x %9.2f us  %s\n", sorted[r].second.seconds,
                 sorted[r].second.calls, 1e6 * sorted[r].second.seconds / sorted[r].second.calls,
                 sorted[r].first.c_str());
}
}  // namespace

extern "C" {
void kokkosp_init_library(int, uint64_t, uint32_t, void*) {}
void kokkosp_begin_parallel_for(const char* name, uint32_t, uint64_t*) { begin(name); }
void kokkosp_end_parallel_for(uint64_t) { end(); }
void kokkosp_begin_parallel_reduce(const char* name, uint32_t, uint64_t*) { begin(name); }
void kokkosp_end_parallel_reduce(uint64_t) { end(); }
void kokkosp_begin_parallel_scan(const char* name, uint32_t, uint64_t*) { begin(name); }
void kokkosp_end_parallel_scan(uint64_t) { end(); }
void kokkosp_finalize_library() {
  print("kernels", kernels, 30);
  print("host gaps before a kernel (kernel before -> kernel after)", gaps, 30);
  for (int b = 0; b < kBins; ++b)
    std::fprintf(stderr, "gaps %-10s %9ld  %.4f s\n", kBinNames[b], bins[b].calls, bins[b].seconds);
}
}
