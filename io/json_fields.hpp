// Typed reading of JSON objects with path-aware, one-line error messages (lsi::InputError).
// Every message names the dotted JSON path, the offending value and what is allowed, e.g.
//   `landslide.thickness_m = -3: must be > 0 (m)`
//   `barrier.height_m: missing (required: number > 0, m)`
//   `landslide.thicknes_m: unknown key (allowed: thickness_m, velocity_m_s, ...)`
// Used by the scene parser (io/scene_parser.cpp); reusable for other JSON inputs.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/input_error.hpp"
#include "model/messages.hpp"

namespace lsi::json_fields {

using lsi::format_number;  // model/messages.hpp
using lsi::format_value;
// "parent.key"; a key that is not a plain identifier is written as parent["the key"].
std::string join_path(std::string_view parent, std::string_view key);

[[noreturn]] void fail(const std::string& message);  // throws InputError(message)

// A numeric interval with optional bounds and a unit for the messages. A bound may carry a label
// (e.g. "base_width_m") when it comes from another field; messages then show "label = value".
struct Bound {
  double value = 0.0;
  bool inclusive = true;
  std::string label;
};
struct Range {
  std::optional<Bound> lo;
  std::optional<Bound> hi;
  std::string unit;  // "m", "m/s", ... or empty for dimensionless
  bool contains(double v) const;
  std::string describe() const;  // "> 0", ">= 0", "in (0, 1)", "in [0, 90)", "any number"
};
Range any_number(std::string unit = {});
Range greater_than(double lo, std::string unit = {});
Range at_least(double lo, std::string unit = {});
// interval('(', 0, 1, ']') is (0, 1]; open/close are '(' / '[' and ')' / ']'.
Range interval(char open, double lo, double hi, char close, std::string unit = {});

// Checks one JSON value (already looked up) against a type and a range; `path` names it.
double check_number(const nlohmann::json& v, const std::string& path, const Range& range);
long long check_integer(const nlohmann::json& v, const std::string& path, const Range& range);

// A view of one JSON object at `path`, whose keys were checked against an allowed list on
// construction. Accessors throw InputError with the full dotted path.
class ObjectReader {
 public:
  // Throws if `j` is not an object or has a key outside `allowed`.
  ObjectReader(const nlohmann::json& j, std::string path, std::vector<std::string> allowed);

  const nlohmann::json& json() const { return *j_; }
  const std::string& path() const { return path_; }
  std::string path_of(std::string_view key) const { return join_path(path_, key); }
  bool has(const std::string& key) const { return j_->contains(key); }
  const nlohmann::json* find(const std::string& key) const;

  // Numbers: required / optional / with a default; JSON numbers only, finite, inside `range`.
  double number(const std::string& key, const Range& range) const;
  std::optional<double> optional_number(const std::string& key, const Range& range) const;
  double number_or(const std::string& key, double fallback, const Range& range) const;
  long long integer(const std::string& key, const Range& range) const;  // required

  std::string string(const std::string& key) const;  // required, non-empty, no control characters
  std::optional<std::string> optional_string(const std::string& key) const;  // non-empty if set
  // A string out of `options`; `fallback` when absent (required when fallback is nullopt).
  std::string choice(const std::string& key, const std::vector<std::string>& options,
                     std::optional<std::string> fallback = std::nullopt) const;
  bool boolean_or(const std::string& key, bool fallback) const;

  ObjectReader object(const std::string& key, std::vector<std::string> allowed) const;
  std::optional<ObjectReader> optional_object(const std::string& key,
                                              std::vector<std::string> allowed) const;

  // `path.key = value: what` (the key must be present).
  [[noreturn]] void fail_at(const std::string& key, const std::string& what) const;
  // `path.key: missing (required: requirement)`.
  [[noreturn]] void fail_missing(const std::string& key, const std::string& requirement) const;

 private:
  const nlohmann::json& require(const std::string& key, const std::string& requirement) const;
  const nlohmann::json* j_;
  std::string path_;
  std::vector<std::string> allowed_;
};

// Parses a whole JSON document. Throws InputError, one line, prefixed `SOURCE:LINE:COLUMN: `
// where the parser stopped (LINE/COLUMN 1-based, of the last character read):
//   malformed JSON        -> `SOURCE:L:C: malformed JSON: <reason>` (+ a note for NaN/Infinity)
//   number overflow       -> `SOURCE:L:C: landslide.thickness_m = 1e999: must be finite (...)`
//   duplicate object key  -> `SOURCE: landslide.thickness_m: duplicate key (...)`
// `source` names the input in the messages (usually the file path).
nlohmann::json parse_json_document(const std::string& text, const std::string& source);

// "a, b, c" and "\"a\", \"b\"" for messages.
std::string join(const std::vector<std::string>& items, bool quoted = false);

}  // namespace lsi::json_fields
