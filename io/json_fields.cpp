#include "io/json_fields.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace lsi::json_fields {

namespace {

using nlohmann::json;

constexpr std::size_t kMaxValueChars = 60;
// Deepest nesting of arrays and objects a document may have. Scenes and studies need fewer than
// 10 levels; nlohmann::json copies, compares and writes values recursively, so a document nested
// 100000 levels deep (200 kB of "[[[...]]]") would overflow the stack there.
constexpr std::size_t kMaxNestingDepth = 100;

bool is_identifier(std::string_view key) {
  if (key.empty()) return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

std::string dump_one_line(const json& v) {
  // error_handler_t::replace: invalid UTF-8 in a string must not turn an error into a crash.
  return v.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string unit_suffix(const std::string& unit) { return unit.empty() ? "" : " (" + unit + ")"; }

std::string describe_bound(const Bound& b) {
  return b.label.empty() ? format_number(b.value) : b.label + " = " + format_number(b.value);
}

std::string number_requirement(const Range& range) {
  std::string r = range.lo || range.hi ? "number " + range.describe() : "number";
  if (!range.unit.empty()) r += ", " + range.unit;
  return r;
}

std::string display_path(const std::string& path) { return path.empty() ? "(top level)" : path; }

}  // namespace

std::string join_path(std::string_view parent, std::string_view key) {
  const std::string k(key);
  if (!is_identifier(key)) {
    const std::string quoted = "[" + dump_one_line(json(k)) + "]";
    return parent.empty() ? quoted : std::string(parent) + quoted;
  }
  return parent.empty() ? k : std::string(parent) + "." + k;
}

std::string join(const std::vector<std::string>& items, bool quoted) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += ", ";
    out += quoted ? "\"" + items[i] + "\"" : items[i];
  }
  return out;
}

void fail(const std::string& message) { throw InputError(message); }

// ---- Range ------------------------------------------------------------------------------------

bool Range::contains(double v) const {
  if (lo && (lo->inclusive ? v < lo->value : v <= lo->value)) return false;
  if (hi && (hi->inclusive ? v > hi->value : v >= hi->value)) return false;
  return true;
}

std::string Range::describe() const {
  if (lo && hi) {
    return std::string("in ") + (lo->inclusive ? "[" : "(") + describe_bound(*lo) + ", " +
           describe_bound(*hi) + (hi->inclusive ? "]" : ")");
  }
  if (lo) return (lo->inclusive ? ">= " : "> ") + describe_bound(*lo);
  if (hi) return (hi->inclusive ? "<= " : "< ") + describe_bound(*hi);
  return "any number";
}

Range any_number(std::string unit) { return Range{std::nullopt, std::nullopt, std::move(unit)}; }
Range greater_than(double lo, std::string unit) {
  return Range{Bound{lo, false, {}}, std::nullopt, std::move(unit)};
}
Range at_least(double lo, std::string unit) {
  return Range{Bound{lo, true, {}}, std::nullopt, std::move(unit)};
}
Range interval(char open, double lo, double hi, char close, std::string unit) {
  return Range{Bound{lo, open == '[', {}}, Bound{hi, close == ']', {}}, std::move(unit)};
}

// ---- value checks -----------------------------------------------------------------------------

double check_number(const json& v, const std::string& path, const Range& range) {
  if (!v.is_number()) fail(path + " = " + format_value(v) + ": must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(path + " = " + format_value(v) + ": must be finite");
  if (!range.contains(d)) {
    fail(path + " = " + format_value(v) + ": must be " + range.describe() +
         unit_suffix(range.unit));
  }
  return d;
}

long long check_integer(const json& v, const std::string& path, const Range& range) {
  if (!v.is_number()) fail(path + " = " + format_value(v) + ": must be an integer");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(path + " = " + format_value(v) + ": must be finite");
  if (std::floor(d) != d) fail(path + " = " + format_value(v) + ": must be an integer");
  if (!range.contains(d)) {
    fail(path + " = " + format_value(v) + ": must be an integer " + range.describe() +
         unit_suffix(range.unit));
  }
  if (std::fabs(d) > 9.0e15) fail(path + " = " + format_value(v) + ": integer too large");
  if (v.is_number_integer()) return v.get<long long>();
  return static_cast<long long>(d);
}

// ---- ObjectReader -----------------------------------------------------------------------------

ObjectReader::ObjectReader(const nlohmann::json& j, std::string path,
                           std::vector<std::string> allowed)
    : j_(&j), path_(std::move(path)), allowed_(std::move(allowed)) {
  if (!j.is_object()) fail(display_path(path_) + " = " + format_value(j) + ": must be an object");
  for (const auto& item : j.items()) {
    if (std::find(allowed_.begin(), allowed_.end(), item.key()) == allowed_.end()) {
      fail(path_of(item.key()) + ": unknown key (allowed: " + join(allowed_) + ")");
    }
  }
}

const nlohmann::json* ObjectReader::find(const std::string& key) const {
  const auto it = j_->find(key);
  return it == j_->end() ? nullptr : &*it;
}

const nlohmann::json& ObjectReader::require(const std::string& key,
                                            const std::string& requirement) const {
  const nlohmann::json* v = find(key);
  if (!v) fail_missing(key, requirement);
  return *v;
}

void ObjectReader::fail_at(const std::string& key, const std::string& what) const {
  const nlohmann::json* v = find(key);
  fail(path_of(key) + (v ? " = " + format_value(*v) : std::string()) + ": " + what);
}

void ObjectReader::fail_missing(const std::string& key, const std::string& requirement) const {
  fail(path_of(key) + ": missing (required: " + requirement + ")");
}

double ObjectReader::number(const std::string& key, const Range& range) const {
  return check_number(require(key, number_requirement(range)), path_of(key), range);
}

std::optional<double> ObjectReader::optional_number(const std::string& key,
                                                    const Range& range) const {
  const nlohmann::json* v = find(key);
  if (!v) return std::nullopt;
  return check_number(*v, path_of(key), range);
}

double ObjectReader::number_or(const std::string& key, double fallback, const Range& range) const {
  return optional_number(key, range).value_or(fallback);
}

long long ObjectReader::integer(const std::string& key, const Range& range) const {
  std::string requirement = "integer " + range.describe();
  if (!range.unit.empty()) requirement += ", " + range.unit;
  return check_integer(require(key, requirement), path_of(key), range);
}

std::string ObjectReader::string(const std::string& key) const {
  const nlohmann::json& v = require(key, "non-empty string");
  if (!v.is_string()) fail_at(key, "must be a string");
  std::string s = v.get<std::string>();
  if (s.empty()) fail_at(key, "must be a non-empty string");
  // Names and labels reach terminals and file names: no control characters (escape sequences).
  for (const char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      fail_at(key, "must not contain control characters (a line break, a tab, an escape)");
  return s;
}

std::optional<std::string> ObjectReader::optional_string(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return string(key);
}

std::string ObjectReader::choice(const std::string& key, const std::vector<std::string>& options,
                                 std::optional<std::string> fallback) const {
  const std::string allowed = "one of " + join(options, true);
  const nlohmann::json* v = find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail_missing(key, allowed);
  }
  if (!v->is_string()) fail_at(key, "must be a string, " + allowed);
  std::string s = v->get<std::string>();
  if (std::find(options.begin(), options.end(), s) == options.end())
    fail_at(key, "must be " + allowed);
  return s;
}

bool ObjectReader::boolean_or(const std::string& key, bool fallback) const {
  const nlohmann::json* v = find(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail_at(key, "must be a boolean (true or false)");
  return v->get<bool>();
}

ObjectReader ObjectReader::object(const std::string& key, std::vector<std::string> allowed) const {
  return ObjectReader(require(key, "object"), path_of(key), std::move(allowed));
}

std::optional<ObjectReader> ObjectReader::optional_object(const std::string& key,
                                                          std::vector<std::string> allowed) const {
  const nlohmann::json* v = find(key);
  if (!v) return std::nullopt;
  return ObjectReader(*v, path_of(key), std::move(allowed));
}

// ---- whole documents --------------------------------------------------------------------------

namespace {

// "LINE:COLUMN" of the character at 1-based byte offset `byte` (the last one the parser read).
std::string line_column(const std::string& text, std::size_t byte) {
  const std::size_t pos = std::min(byte > 0 ? byte - 1 : 0, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < pos; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return std::to_string(line) + ":" + std::to_string(pos - line_start + 1);
}

// Whether the word around 1-based byte offset `byte` is NaN / Infinity / -Infinity (or nan, inf).
bool near_non_finite_literal(const std::string& text, std::size_t byte) {
  const std::size_t pos = std::min(byte > 0 ? byte - 1 : 0, text.size());
  const auto word_char = [](char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '-' || c == '+';
  };
  std::size_t start = pos;
  while (start > 0 && word_char(text[start - 1])) --start;
  std::size_t end = start;
  while (end < text.size() && word_char(text[end])) ++end;
  std::string word = text.substr(start, end - start);
  if (!word.empty() && (word[0] == '-' || word[0] == '+')) word.erase(0, 1);
  if (word.empty()) return false;
  std::string lower = word;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word[0] == 'N' || word[0] == 'I' || lower.rfind("nan", 0) == 0 ||
         lower.rfind("inf", 0) == 0;
}

// Builds the DOM like nlohmann's own parser, but keeps the JSON path of the value being read so
// that number overflow and duplicate keys can be reported by path.
class PathTrackingBuilder : public nlohmann::json_sax<nlohmann::json> {
 public:
  nlohmann::json root;
  std::string error;  // set when parsing stopped; already formatted (without the source prefix)
  std::size_t error_byte = 0;
  bool error_has_position = false;

  explicit PathTrackingBuilder(const std::string& text) : text_(text) {}

  bool null() override { return add(nullptr); }
  bool boolean(bool v) override { return add(v); }
  bool number_integer(number_integer_t v) override { return add(v); }
  bool number_unsigned(number_unsigned_t v) override { return add(v); }
  bool number_float(number_float_t v, const string_t& literal) override {
    if (!std::isfinite(v)) {  // nlohmann versions that map overflow to inf instead of failing
      error = value_path() + " = " + literal + ": must be finite (the number overflows a double)";
      return false;
    }
    return add(v);
  }
  bool string(string_t& v) override { return add(v); }
  bool binary(binary_t& v) override { return add(nlohmann::json::binary(v)); }
  bool start_object(std::size_t) override { return open(nlohmann::json::object()); }
  bool key(string_t& k) override {
    Frame& top = frames_.back();
    if (top.container->contains(k)) {
      top.key = k;
      error = value_path() + ": duplicate key (each key may appear only once)";
      return false;
    }
    top.key = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(nlohmann::json::array()); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::json::exception& ex) override {
    error_byte = position;
    error_has_position = true;
    if (ex.id == 406) {  // out_of_range.406: number overflow, e.g. 1e999
      error = line_column(text_, position) + ": " + value_path() + " = " + last_token +
              ": must be finite (the number overflows a double)";
      return false;
    }
    std::string reason = ex.what();
    const std::size_t at = reason.find("parse error");
    if (at != std::string::npos) {
      const std::size_t colon = reason.find(": ", at);
      if (colon != std::string::npos) reason = reason.substr(colon + 2);
    }
    error = line_column(text_, position) + ": malformed JSON: " + reason;
    if (near_non_finite_literal(text_, position)) {
      error += " (NaN and Infinity are not valid JSON numbers)";
    }
    return false;
  }

 private:
  struct Frame {
    nlohmann::json* container;
    std::string key;  // objects: the key of the value being read
  };

  // Dotted path of the value being read (the next array element for an array on top).
  std::string value_path() const {
    std::string path;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.container->is_object()) {
        path = join_path(path, f.key);
      } else {
        const std::size_t n = f.container->size();
        const std::size_t index = i + 1 < frames_.size() ? n - 1 : n;
        path += "[" + std::to_string(index) + "]";
      }
    }
    return path.empty() ? "(top level)" : path;
  }

  nlohmann::json* insert(nlohmann::json&& v) {
    if (frames_.empty()) {
      root = std::move(v);
      return &root;
    }
    Frame& top = frames_.back();
    if (top.container->is_array()) {
      top.container->push_back(std::move(v));
      return &top.container->back();
    }
    nlohmann::json& slot = (*top.container)[top.key];
    slot = std::move(v);
    return &slot;
  }
  bool add(nlohmann::json v) {
    insert(std::move(v));
    return true;
  }
  // Pointers to open containers stay valid: a parent only grows after its open child is closed.
  bool open(nlohmann::json&& container) {
    if (frames_.size() >= kMaxNestingDepth) {
      std::string path = value_path();
      if (path.size() > kMaxValueChars) path = path.substr(0, kMaxValueChars - 3) + "...";
      error = path + ": nested too deep (allowed: at most " + std::to_string(kMaxNestingDepth) +
              " levels of arrays and objects)";
      return false;
    }
    frames_.push_back(Frame{insert(std::move(container)), {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }

  const std::string& text_;
  std::vector<Frame> frames_;
};

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& source) {
  PathTrackingBuilder builder(text);
  const bool ok = nlohmann::json::sax_parse(text, &builder);
  if (!ok || !builder.error.empty()) {
    fail(source + ":" + (builder.error_has_position ? "" : " ") +
         (builder.error.empty() ? "malformed JSON" : builder.error));
  }
  return std::move(builder.root);
}

}  // namespace lsi::json_fields
