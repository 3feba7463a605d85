// Where the impacts' energy goes: the fastest reference flow against the earth barrier
// (scenes/former-reference/L3-B3.json at h / 4), dry and saturated, with the transfer dissipation
// accounted (kernels/mpm/transfer_dissipation.hpp). Its energy residual, -4 % dry and -17 %
// saturated, is the kinetic energy lost in the grid transfers where streams of different
// velocity merge: with that loss booked, what is left is a fraction of a percent.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <string>

#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "stability/stability_support.hpp"

namespace {
using namespace lsi::stability;

json scene(const std::string& phases) {
  return patched(
      fast_flow_on_earth_barrier_h4(),
      R"({"methods": {"mpm": {"transfer_dissipation": true, "phases": ")" + phases + R"("}}})");
}

class TransferDissipationImpact : public ::testing::TestWithParam<const char*> {};

TEST_P(TransferDissipationImpact, ExplainsTheEnergyResidual) {
  const lsi::MpmOutcome out = lsi::run_mpm_case(lsi::impact_case(scene_of(scene(GetParam()))));
  ASSERT_TRUE(out.finished()) << out.status();
  const auto& r = out.result;
  const auto& residual = r.series.at("energy_residual").values;
  const auto& unexplained = r.series.at("energy_residual_unexplained").values;
  const double res_min = *std::min_element(residual.begin(), residual.end());
  const double un_min = *std::min_element(unexplained.begin(), unexplained.end());
  const double un_max = *std::max_element(unexplained.begin(), unexplained.end());
  const double lost = r.series.at("transfer_dissipation").values.back();
  std::cout << "[ L3-B3 h/4 " << GetParam() << " ] energy residual down to " << res_min
            << "; transfer dissipation " << lost / 1e6 << " MJ/m; unexplained " << un_min << " .. "
            << un_max << "\n";
  // The residual is large (measured -4.2 % dry, -16.8 % saturated)...
  EXPECT_LT(res_min, -0.02);
  // ...the transfers lose energy (measured 0.60 and 2.18 MJ/m, against 7.6 MJ/m of initial
  // kinetic energy)...
  EXPECT_GT(lost, 0.0);
  // ...and with that loss booked the balance closes within 1 % at every output (measured -0.05
  // .. +0.14 % dry, -0.02 .. +0.49 % saturated: the explicit time integration and the contact),
  // while the residual itself reaches 4 and 17 %.
  EXPECT_GT(un_min, -0.01);
  EXPECT_LT(un_max, 0.01);
  EXPECT_DOUBLE_EQ(r.scalars.transfer_dissipation_j_per_m.value(), lost);
}

INSTANTIATE_TEST_SUITE_P(Phases, TransferDissipationImpact, ::testing::Values("dry", "saturated"));

}  // namespace
