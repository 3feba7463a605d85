#include "model/method_result.hpp"

#include <stdexcept>

namespace lsi {
namespace {
struct Token {
  EndState state;
  const char* text;
};
constexpr Token kTokens[] = {
    {EndState::None, ""},
    {EndState::AtRest, "at_rest"},
    {EndState::EndTimeLandslideMoving, "end_time_landslide_moving"},
    {EndState::EndTimeBarrierSliding, "end_time_barrier_sliding"},
    {EndState::BarrierLeftDomain, "barrier_left_domain"},
    {EndState::Unstable, "unstable"},
};
}  // namespace

const char* end_state_token(EndState s) {
  for (const Token& t : kTokens)
    if (t.state == s) return t.text;
  return "";
}

EndState end_state_from_token(const std::string& token) {
  for (const Token& t : kTokens)
    if (token == t.text) return t.state;
  throw std::invalid_argument("unknown end state '" + token + "'");
}

const std::vector<HistoryField>& history_fields() {
  static const std::vector<HistoryField> fields = {
      {"time", &MethodResult::time, "s", "time of each sample"},
      {"force", &MethodResult::force, "N/m",
       "impact force per metre of barrier width, normal to the impacted face"},
      {"force_horizontal", &MethodResult::force_horizontal, "N/m",
       "horizontal component of the impact force per metre of barrier width"},
      {"force_vertical", &MethodResult::force_vertical, "N/m",
       "vertical component of the impact force per metre of barrier width, positive downwards on "
       "the barrier"},
      {"landslide_kinetic_energy", &MethodResult::landslide_kinetic_energy, "J/m",
       "kinetic energy of the landslide per metre of width"},
      {"barrier_velocity", &MethodResult::barrier_velocity, "m/s", "velocity of the barrier"},
      {"barrier_displacement", &MethodResult::barrier_displacement, "m",
       "displacement of the barrier"},
  };
  return fields;
}

const std::vector<SummaryField>& summary_fields() {
  static const std::vector<SummaryField> fields = {
      {"peak_force", &MethodResult::peak_force, "N/m",
       "largest impact force per metre of barrier width, normal to the impacted face"},
      {"rise_time", &MethodResult::rise_time, "s", "time from first contact to the peak force"},
      {"impact_duration", &MethodResult::impact_duration, "s",
       "duration of the impact (of the force pulse)"},
      {"final_displacement", &MethodResult::final_displacement, "m",
       "displacement of the barrier when it has stopped; +inf for a barrier that never stops"},
  };
  return fields;
}

}  // namespace lsi
