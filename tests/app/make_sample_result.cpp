// Writes a small synthetic result file (two methods, physically shaped histories) for the plot
// script test: `make_sample_result OUT.h5`.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

#include "io/hdf5_results.hpp"

namespace {

// Triangular force pulse (rise T1, total duration T2), kinetic energy decaying as the landslide is
// stopped, barrier displacement growing towards a final value.
lsi::MethodResult synthetic(const std::string& method, double peak_n_per_m, double t1, double t2,
                            double energy0_j_per_m, double final_disp_m) {
  lsi::MethodResult r;
  r.method = method;
  const int n = 201;
  const double t_end = 1.5 * t2;
  for (int i = 0; i < n; ++i) {
    const double t = t_end * i / (n - 1);
    const double f = t <= t1   ? peak_n_per_m * t / t1
                     : t <= t2 ? peak_n_per_m * (t2 - t) / (t2 - t1)
                               : 0.0;
    const double s = std::min(t / t2, 1.0);  // progress of the impact
    r.time.push_back(t);
    r.force.push_back(f);
    r.force_horizontal.push_back(f * std::sin(80.0 * std::numbers::pi / 180.0));
    r.force_vertical.push_back(f * std::cos(80.0 * std::numbers::pi / 180.0));
    r.landslide_kinetic_energy.push_back(energy0_j_per_m * std::exp(-4.0 * t / t2));
    r.barrier_velocity.push_back(final_disp_m * 2.0 * (1.0 - s) / t2);
    r.barrier_displacement.push_back(final_disp_m * s * (2.0 - s));
  }
  r.peak_force = peak_n_per_m;
  r.rise_time = t1;
  r.impact_duration = t2;
  r.final_displacement = final_disp_m;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.h5\n", argv[0]);
    return 2;
  }
  try {
    const nlohmann::json scene = {
        {"name", "synthetic sample"},
        {"landslide", {{"thickness_m", 2.0}, {"velocity_m_s", 10.0}, {"density_kg_m3", 2000.0}}},
        {"barrier",
         {{"height_m", 5.0},
          {"base_width_m", 4.0},
          {"top_width_m", 2.0},
          {"density_kg_m3", 2400.0}}},
        {"methods",
         {{"empirical", nlohmann::json::object()}, {"analytical", nlohmann::json::object()}}}};
    auto empirical = synthetic("empirical", 3.2e5, 0.25, 1.1, 9.0e5, 0.12);
    empirical.barrier_velocity.clear();  // exercises "method lacks a dataset"
    empirical.scalars.froude_number = 2.26;
    auto analytical = synthetic("analytical", 2.7e5, 0.3, 1.4, 9.0e5, 0.18);
    lsi::write_results(argv[1], scene, {empirical, analytical});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_sample_result: %s\n", e.what());
    return 1;
  }
  std::printf("%s\n", argv[1]);
  return 0;
}
