#include "io/text_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "io/hdf5_io.hpp"
#include "io/output_paths.hpp"
#include "io/temporary_files.hpp"

namespace lsi {

void write_text_atomically(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  const std::string tmp = temporary_path(path);
  const auto fail = [&](const std::string& what) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error("cannot write '" + path + "': " + what);
  };
  if (const std::string why = unsafe_output_reason(path); !why.empty()) fail(why);
  remove_stale_temporaries(path);
  const TemporaryFileGuard guard(tmp);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) fail("cannot create '" + tmp + "': " + std::strerror(errno));
    f << text;
    f.flush();
    if (!f) fail("cannot write '" + tmp + "'");
  }
  hdf5::fsync_file(tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    fail("cannot rename '" + tmp + "' onto it: " + std::strerror(errno));
  hdf5::fsync_directory(target.has_parent_path() ? target.parent_path() : fs::path("."));
}

}  // namespace lsi
