#include "io/sweep_csv.hpp"

#include <charconv>
#include <cmath>

#include "io/text_file.hpp"

namespace lsi {
namespace {

void append_number(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  out.append(buf, res.ptr);
}

}  // namespace

void write_sweep_table_csv(const std::string& path, const SweepTable& t) {
  std::string text = "index";
  for (const auto& p : t.input_paths) text += "," + p;
  for (const auto& c : t.output_columns) text += "," + c;
  text += ",status\n";
  text.reserve(text.size() +
               t.rows() * (24 * (t.inputs.size() + t.outputs.size()) + 24));  // ~24 per number
  for (std::size_t i = 0; i < t.rows(); ++i) {
    text += std::to_string(t.index[i]);
    for (const auto& column : t.inputs) {
      text += ',';
      append_number(text, column[i]);
    }
    for (const auto& column : t.outputs) {
      text += ',';
      append_number(text, column[i]);
    }
    text += ',';
    text += std::to_string(static_cast<int>(t.status[i]));
    text += '\n';
  }
  write_text_atomically(path, text);
}

}  // namespace lsi
