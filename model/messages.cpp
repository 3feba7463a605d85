#include "model/messages.hpp"

#include <charconv>
#include <cmath>

namespace lsi {
namespace {
constexpr std::size_t kMaxValueChars = 60;
}  // namespace

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  // Integral values plainly ("1000000", not "1e+06"); others in their shortest round-trip form.
  const bool integral = std::floor(v) == v && std::fabs(v) < 1e16;
  const auto res = integral ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                            : std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string format_value(const nlohmann::json& v) {
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (!std::isfinite(d)) return format_number(d);
  }
  std::string s = v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (s.size() > kMaxValueChars) s = s.substr(0, kMaxValueChars - 3) + "...";
  return s;
}

}  // namespace lsi
