#include "io/output_paths.hpp"

#include <filesystem>
#include <system_error>

#include "io/json_fields.hpp"
#include "model/scene.hpp"

namespace lsi {
namespace fs = std::filesystem;

namespace {
std::string shown(const std::string& s) { return json_fields::format_value(s); }

const char* kind_of(fs::file_type t) {
  switch (t) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::fifo:
      return "a named pipe";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}
}  // namespace

std::string unsafe_output_reason(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows links
  if (ec || st.type() == fs::file_type::not_found || st.type() == fs::file_type::regular) return "";
  return std::string("it exists and is ") + kind_of(st.type()) +
         ", which the output would replace (only a regular file is replaced)";
}

void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& inputs) {
  if (path.empty()) json_fields::fail(option + " = \"\": must be a file path");
  const std::string why = unsafe_output_reason(path);
  if (!why.empty()) json_fields::fail(option + " = " + shown(path) + ": " + why);
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  for (const auto& in : inputs) {
    std::error_code e2;
    if (fs::exists(in, e2) && fs::equivalent(path, in, e2))
      json_fields::fail(option + " = " + shown(path) + ": is the input " + shown(in) +
                        ", which the output would destroy: choose another path");
  }
}

void check_output_directory(const std::string& option, const std::string& dir) {
  if (dir.empty()) json_fields::fail(option + " = \"\": must be a directory path");
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (ec || st.type() == fs::file_type::not_found || st.type() == fs::file_type::directory) return;
  json_fields::fail(option + " = " + shown(dir) + ": exists and is " + kind_of(st.type()) +
                    ", not a directory");
}

void check_file_name(const std::string& what, const std::string& name) {
  auto fail = [&](const std::string& why) {
    json_fields::fail(what + " = " + shown(name) + ": " + why +
                      " (it names a file: a plain file name, at most 200 bytes, without '/', '\\', "
                      "control characters, '.' or '..')");
  };
  if (name.empty()) fail("empty");
  if (name.size() > 200) fail("longer than 200 bytes");
  if (name == "." || name == "..") fail("not a file name");
  for (const char c : name) {
    if (c == '/' || c == '\\') fail("contains a path separator");
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) fail("contains a control character");
  }
}

}  // namespace lsi
