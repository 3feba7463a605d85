#include "json_mutator.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>
#include <utility>

namespace lsi::fuzz {
namespace {

using nlohmann::json;
using Pointer = json::json_pointer;

// Seeds longer than this are only edited byte-wise (a regression input may nest 100000 levels;
// the mutator must not walk it recursively).
constexpr std::size_t kMaxJsonSeedBytes = 16384;
// Marker strings: a value or a key set to one of them is written, then its quoted text replaced.
const std::string kValueMarker = "\x01lsi-value\x01";
const std::string kKeyMarker = "\x01lsi-key\x01";

const char* const kNastyLiterals[] = {
    "NaN",
    "nan",
    "Infinity",
    "-Infinity",
    "inf",
    "1e999",
    "-1e999",
    "1e308",
    "-1e308",
    "1.8e308",
    "5e-324",
    "1e-320",
    "0",
    "-0",
    "-0.0",
    "-1",
    "1",
    "0.5",
    "2.5",
    "4.0",
    "64",
    "65",
    "1e6",
    "1000001",
    "9e15",
    "9.000000000000002e15",
    "1e16",
    "9223372036854775807",
    "9223372036854775808",
    "-9223372036854775809",
    "18446744073709551615",
    "18446744073709551616",
    "1e19",
    "-1e19",
    "\"12\"",
    "\"\"",
    "\"x\"",
    "true",
    "false",
    "null",
    "[]",
    "{}",
    "[1, 2]",
    "[1, 2, 3]",
    "[[1, 2], [3, 4]]",
    "{\"a\": 1}",
    "[0.5, 0.5]",
    "1e-300",
    "-1e-300",
    "90",
    "89.99999999999999",
    "0.49999999999999994",
    "1e300",
    "2147483648",
    "4294967296",
    "1e-9",
};

// Strings the parsers give a meaning to, and some that are almost right.
const char* const kStrings[] = {
    "front-body-tail",
    "rectangle",
    "hydrostatic",
    "hydrodynamic",
    "mixed",
    "apic",
    "flip",
    "pic",
    "duplicated",
    "atomic",
    "saturated",
    "dry",
    "semi-implicit",
    "explicit",
    "linear-elastic",
    "mohr-coulomb",
    "monte-carlo",
    "latin-hypercube",
    "sobol",
    "grid",
    "constant",
    "uniform",
    "normal",
    "lognormal",
    "truncated-normal",
    "discrete",
    "empirical",
    "analytical",
    "literature",
    "mpm",
    "peak_force",
    "rise_time",
    "impact_duration",
    "final_displacement",
    "mean",
    "exceedance",
    "/landslide/thickness_m",
    "/landslide/velocity_m_s",
    "/landslide/shape/body_squares",
    "/landslide/shape/length_m",
    "/landslide/material/porosity",
    "/barrier/height_m",
    "/barrier/top_width_m",
    "/barrier/face_angle_deg",
    "/barrier/mass_kg_per_m",
    "/barrier/face_friction",
    "/methods/empirical/tau",
    "/methods/analytical/lambda",
    "/methods/mpm/cell_size_m",
    "/methods/mpm/courant",
    "/methods/mpm/",
    "/methods/mpm/x/0",
    "/methods/mpm/x/-",
    "/methods/mpm/a~2",
    "/methods/mpm/a~",
    "/methods/mpm/transfer/x",
    "/methods/mpm/cell_size_m/0",
    "/methods/mpm/xs/01",
    "/methods/mpm/xs/99999999999",
    "/methods/mpm",
    "/landslide",
    "../former-reference/L1-B1.json",
    "../former-reference/L3-B3.json",
    "../examples/rectangle-fixed.json",
    "../examples/impact-small.json",
    "../verification/column-collapse.json",
    "missing.json",
    ".",
    "..",
    "/",
    "",
    " ",
    "a\nb",
    "\xc3\xa9",
    "sand",
    "L1-B1",
};

// Appended to a string to break it in interesting ways.
const char* const kStringSuffixes[] = {
    "~",    "~0", "~1", "~2", "/",        "/0", "/-", "/01", "/99999999999999999999",
    "/x/y", " ",  "\n", "\t", "\xc3\xa9", "\\", "\"",
};

// Keys that the schemas do not know, or almost know.
const char* const kUnknownKeys[] = {
    "bogus",    "thickness_m ", "Thickness_m", "",       " ",    "a\nb",   "\xc3\xa9", "~1",
    "mpm_case", "methods",      "scene",       "inputs", "name", "preset", "a.b",      "[0]",
};

template <std::size_t N>
std::string pick(const char* const (&list)[N], std::size_t i) {
  return list[i % N];
}

std::string replace_first(std::string text, const std::string& what, const std::string& with) {
  const std::size_t at = text.find(what);
  if (at != std::string::npos) text.replace(at, what.size(), with);
  return text;
}

// Every value's pointer, at most `max_depth` levels down (root included).
void collect(const json& j, const Pointer& at, int max_depth, std::vector<Pointer>& out) {
  out.push_back(at);
  if (max_depth == 0) return;
  if (j.is_object()) {
    for (const auto& item : j.items()) collect(item.value(), at / item.key(), max_depth - 1, out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) collect(j[i], at / i, max_depth - 1, out);
  }
}

std::string nested(const std::string& inner, std::size_t levels, bool objects) {
  std::string out;
  out.reserve(inner.size() + levels * (objects ? 7 : 2));
  for (std::size_t i = 0; i < levels; ++i) out += objects ? "{\"a\": " : "[";
  out += inner;
  for (std::size_t i = 0; i < levels; ++i) out += objects ? "}" : "]";
  return out;
}

}  // namespace

JsonMutator::JsonMutator(std::vector<std::string> seeds, std::uint64_t random_seed)
    : seeds_(std::move(seeds)), state_(random_seed ^ 0x9e3779b97f4a7c15ull) {
  if (state_ == 0) state_ = 1;
  if (seeds_.empty()) seeds_.push_back("{}");
}

std::uint64_t JsonMutator::random() {  // xorshift64*
  state_ ^= state_ >> 12;
  state_ ^= state_ << 25;
  state_ ^= state_ >> 27;
  return state_ * 0x2545f4914f6cdd1dull;
}

std::size_t JsonMutator::below(std::size_t n) { return static_cast<std::size_t>(random() % n); }

bool JsonMutator::chance(int percent) { return below(100) < static_cast<std::size_t>(percent); }

std::string JsonMutator::next() { return mutate(seeds_[below(seeds_.size())]); }

std::string JsonMutator::mutate(std::string text) {
  const int edits = 1 + static_cast<int>(below(3));
  for (int e = 0; e < edits; ++e) text = json_edit(text);
  if (chance(20)) text = byte_edit(std::move(text));
  return text;
}

std::string JsonMutator::json_edit(const std::string& text) {
  if (text.size() > kMaxJsonSeedBytes) return byte_edit(text);
  json doc = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) return byte_edit(text);
  std::vector<Pointer> all;
  collect(doc, Pointer(), 64, all);
  std::vector<Pointer> numbers;
  for (const auto& p : all)
    if (doc[p].is_number()) numbers.push_back(p);
  // Numbers are what the range checks are about: half the edits aim at one.
  const Pointer p =
      !numbers.empty() && chance(50) ? numbers[below(numbers.size())] : all[below(all.size())];
  json& value = doc[p];
  const json original = value;
  const bool has_parent = !p.empty();
  const Pointer parent = has_parent ? p.parent_pointer() : Pointer();
  const auto with_value_text = [&](const std::string& literal) {
    value = kValueMarker;
    return replace_first(doc.dump(), json(kValueMarker).dump(), literal);
  };

  switch (below(12)) {
    case 0:
    case 1:
    case 2:
      return with_value_text(pick(kNastyLiterals, below(1000)));
    case 3:
      if (original.is_string() && chance(50)) {
        std::string s = original.get<std::string>();
        const std::string suffix = pick(kStringSuffixes, below(1000));
        s.insert(s.empty() ? 0 : below(s.size() + 1), suffix);
        return with_value_text(json(s).dump(-1, ' ', false, json::error_handler_t::replace));
      }
      return with_value_text(
          json(pick(kStrings, below(1000))).dump(-1, ' ', false, json::error_handler_t::replace));
    case 4: {  // an object member deleted, duplicated, or an unknown key added
      if (!has_parent || !doc[parent].is_object()) return with_value_text("null");
      json& object = doc[parent];
      const std::string key = p.back();
      switch (below(3)) {
        case 0:
          object.erase(key);
          return doc.dump();
        case 1: {
          object[kKeyMarker] = original;
          return replace_first(doc.dump(), json(kKeyMarker).dump() + ":", json(key).dump() + ":");
        }
        default: {
          object[kKeyMarker] = original;
          const std::string unknown = json(pick(kUnknownKeys, below(1000)))
                                          .dump(-1, ' ', false, json::error_handler_t::replace);
          return replace_first(doc.dump(), json(kKeyMarker).dump() + ":", unknown + ":");
        }
      }
    }
    case 5: {  // array surgery
      if (!has_parent || !doc[parent].is_array()) return with_value_text("[]");
      json& array = doc[parent];
      const std::size_t index = std::stoul(p.back());
      switch (below(4)) {
        case 0:
          array.erase(index);
          break;
        case 1:
          array.insert(array.begin() + static_cast<std::ptrdiff_t>(index), original);
          break;
        case 2:
          array = json::array();
          break;
        default:
          while (array.size() < 40) array.push_back(original);
      }
      return doc.dump();
    }
    case 6:
      return with_value_text(chance(50) ? "[" + original.dump() + "]"
                                        : "{\"v\": " + original.dump() + "}");
    case 7: {  // deep nesting; the deepest (stack depth) kinds are rarer, they cost more
      static const std::size_t kLevels[] = {10, 100, 1000, 10000, 100000};
      const std::size_t levels = kLevels[chance(90) ? below(3) : 3 + below(2)];
      return with_value_text(nested(original.dump(), levels, chance(50)));
    }
    case 8:
    case 9: {  // crossover: a value of another seed
      const std::string& other_text = seeds_[below(seeds_.size())];
      if (other_text.size() > kMaxJsonSeedBytes) return with_value_text("{}");
      const json other = json::parse(other_text, nullptr, false);
      if (other.is_discarded()) return with_value_text("{}");
      std::vector<Pointer> others;
      collect(other, Pointer(), 64, others);
      return with_value_text(other[others[below(others.size())]].dump());
    }
    case 10: {  // a number nudged: just inside or outside a bound, scaled, negated
      if (!original.is_number()) return with_value_text(pick(kNastyLiterals, below(1000)));
      const double v = original.get<double>();
      const double nudged[] = {-v,
                               v * 1e6,
                               v / 1e6,
                               v + 1,
                               v - 1,
                               std::nextafter(v, 1e308),
                               std::nextafter(v, -1e308),
                               v * 2,
                               v / 2,
                               std::floor(v) + 0.5};
      return with_value_text(json(nudged[below(std::size(nudged))]).dump());
    }
    default: {  // a sibling's value moved here (a key gets the right type but the wrong meaning)
      if (!has_parent) return with_value_text("{}");
      std::vector<Pointer> siblings;
      collect(doc[parent], Pointer(), 1, siblings);
      return with_value_text(doc[parent][siblings[below(siblings.size())]].dump());
    }
  }
}

std::string JsonMutator::byte_edit(std::string text) {
  static const char kBytes[] = {'"', '{', '}', '[', ']', ',', ':', '\\', '\0', '\xff', '\xc3',
                                'e', '-', '.', '0', '9', 'n', 't', '/',  '~',  ' ',    '\n'};
  if (text.empty()) return std::string(1, kBytes[below(sizeof kBytes)]);
  const std::size_t at = below(text.size());
  const std::size_t len = 1 + below(std::min<std::size_t>(16, text.size() - at));
  switch (below(6)) {
    case 0:
      text[at] = static_cast<char>(text[at] ^ (1 << below(8)));
      break;
    case 1:
      text[at] = kBytes[below(sizeof kBytes)];
      break;
    case 2:
      text.erase(at, len);
      break;
    case 3:
      text.insert(at, text.substr(at, len));
      break;
    case 4:
      text.insert(at, 1, kBytes[below(sizeof kBytes)]);
      break;
    default:
      text.resize(at);
      break;
  }
  return text;
}

}  // namespace lsi::fuzz
