// The files a test writes: a folder of the test program's own under the system's temporary folder
// (its name and the process id, so that the programs ctest runs side by side never share one), and
// a text written into it.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace lsi::testing {

// <temporary folder>/<name>_<pid>, created if missing.
inline std::filesystem::path process_temp_dir(const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / (name + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(d);
  return d;
}

// Writes `text` to `path` (replacing it) and returns the path.
inline std::filesystem::path write_text(const std::filesystem::path& path,
                                        const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

}  // namespace lsi::testing
