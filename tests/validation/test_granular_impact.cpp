// Validation of a dry granular flow's impact on a rigid wall against the hydrodynamic law
// F = alpha rho v^2 h and the values of its dynamic coefficient alpha published for design, with
// the scene of scenes/verification/granular-impact.json run through the driver at three Froude
// numbers Fr = v / (g h)^(1/2).
//
// No flume experiment with a tabulated force or pressure history of a dry granular impact was
// available (docs/vv/validation.md names what was searched), so the comparison is with the law
// and its coefficients, and with the momentum balance of a steady jet:
// 1. The peak force (the largest mean over one output interval), as alpha = F / (rho v^2 h),
//    lies within the design range alpha = 1.5 (Hungr et al. 1984) to 2.5 (Kwan 2012) at every
//    Froude number, and falls as the Froude number grows (as every Froude-dependent law of alpha
//    does).
// 2. Once the front's impact is over, the flow is turned up the wall as a jet: the momentum
//    balance of a steady jet turned through a right angle gives F = rho v^2 h, alpha = 1 (a
//    static pile-up adds to it at low Froude numbers only). The largest mean force over 2.5 h / v
//    (longer than the front's impact, h / v) is that sustained load at Fr = 4.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "io/scene_parser.hpp"
#include "model/scene_methods.hpp"

namespace {

constexpr double kG = 9.81;

struct Impact {
  double alpha_peak;       // peak force / (rho v^2 h)
  double alpha_sustained;  // largest mean over 2.5 h / v, over rho v^2 h
};

Impact run_at_froude(double froude) {
  std::ifstream in(LSI_SOURCE_DIR "/scenes/verification/granular-impact.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  const double h = doc["landslide"]["thickness_m"].get<double>();
  const double rho = doc["landslide"]["density_kg_m3"].get<double>();
  const double v = froude * std::sqrt(kG * h);
  doc["landslide"]["velocity_m_s"] = v;
  doc["methods"]["mpm"]["peak_force_window_s"] = 2.5 * h / v;
  const lsi::SceneRun run = lsi::run_scene_methods(lsi::parse_scene(doc), {"mpm"}, "--methods");
  const lsi::MethodResult& r = run.results.back();
  EXPECT_EQ(r.method, "mpm");
  EXPECT_TRUE(run.mpm_status.empty()) << run.mpm_status;
  const double dynamic = rho * v * v * h;
  return {r.peak_force / dynamic, r.scalars.peak_force_windowed.value_or(NAN) / dynamic};
}

TEST(GranularImpact, DynamicCoefficientWithinPublishedRange) {
  const Impact fr1 = run_at_froude(1.0), fr2 = run_at_froude(2.0), fr4 = run_at_froude(4.0);
  std::cout << "[ granular impact ] alpha at the peak: Fr 1 " << fr1.alpha_peak << ", Fr 2 "
            << fr2.alpha_peak << ", Fr 4 " << fr4.alpha_peak << "; sustained at Fr 4 "
            << fr4.alpha_sustained << "\n";
  // The published design range, without room: at this resolution the values lie inside it by
  // 5 % or more, more than they change between h/4 and h/16 cells (docs/vv/validation.md).
  constexpr double kHungr1984 = 1.5, kKwan2012 = 2.5;
  for (const Impact& i : {fr1, fr2, fr4}) {
    EXPECT_GE(i.alpha_peak, kHungr1984);
    EXPECT_LE(i.alpha_peak, kKwan2012);
  }
  // Higher Froude number, smaller coefficient: the static pile-up's share falls. 5 % between
  // Fr = 1 and 4 is more than the peak's variation with the cell (a few per cent).
  EXPECT_LT(fr4.alpha_peak, 0.95 * fr1.alpha_peak);
  // The steady jet: alpha = 1. 15 %: the incoming flow decelerates on its base (friction 0.3,
  // about 3 m/s^2) while the body passes, and the mean over a finite window of an unsteady
  // load is not the steady value.
  constexpr double kJetRel = 0.15;
  EXPECT_NEAR(fr4.alpha_sustained, 1.0, kJetRel);
}

}  // namespace
