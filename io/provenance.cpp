#include "io/provenance.hpp"

#include "io/hdf5_io.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

#ifndef LSI_VERSION
#define LSI_VERSION "unknown"
#endif

namespace lsi {
namespace {
std::vector<std::string>& stored_command_line() {
  static std::vector<std::string> words;
  return words;
}
}  // namespace

void set_command_line(int argc, const char* const* argv) {
  std::vector<std::string>& words = stored_command_line();
  words.clear();
  for (int k = 0; k < argc && argv[k] != nullptr; ++k) words.emplace_back(argv[k]);
}

const std::vector<std::string>& command_line() { return stored_command_line(); }

std::string shell_quoted(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) {
    if (!out.empty()) out += ' ';
    const bool plain = !w.empty() && w.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_-+=/.,:@%") == std::string::npos;
    if (plain) {
      out += w;
      continue;
    }
    out += '\'';
    for (char c : w) {
      if (c == '\'')
        out += "'\\''";
      else
        out += c;
    }
    out += '\'';
  }
  return out;
}

void write_provenance(hid_t file) {
  hdf5::write_string_attribute(file, "lsi_version", LSI_VERSION);
  hdf5::write_string_attribute(file, "git_revision", LSI_GIT_REVISION);
  hdf5::write_string_attribute(file, "command_line", shell_quoted(command_line()));
  hdf5::write_string_array_attribute(file, "argv", command_line());
}

}  // namespace lsi
