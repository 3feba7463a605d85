// Numbers and values as the messages show them.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace lsi {

// Shortest round-trip decimal form of v ("2.5", "1e-09"); integral values plainly ("1000000");
// "inf", "-inf", "nan" when not finite.
std::string format_number(double v);
// A JSON value on one line as it would be written (strings quoted and escaped, invalid UTF-8
// replaced), long values shortened with "...", non-finite numbers as inf/-inf/nan.
std::string format_value(const nlohmann::json& v);

}  // namespace lsi
