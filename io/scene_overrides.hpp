// Command-line overrides of a scene: `--set /json/pointer=value`, applied to the scene document
// before it is parsed, so the parser checks the result as it checks a file (unknown keys, ranges).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lsi {

// Applies each "POINTER=VALUE" in order. VALUE is read as JSON (a number, true, "text", {...});
// what is not JSON is taken as a string. The pointer's parent must exist in the document (an
// object, or an array with the index in range or "-" to append). Throws InputError naming the
// override: `--set 'x': must be /json/pointer=value`, `--set /a/b=1: /a is not in the scene`.
void apply_overrides(nlohmann::json& doc, const std::vector<std::string>& overrides);

}  // namespace lsi
