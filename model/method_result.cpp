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

}  // namespace lsi
