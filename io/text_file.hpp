// Writes a text file atomically: the text goes to `<path>.tmp.<pid>` in the same directory, which
// is flushed, fsync'ed and renamed onto `path`, so `path` is either the old file or the complete new
// one (a run killed meanwhile leaves no half-written summary). Missing parent directories are
// created. Throws std::runtime_error("cannot write '<path>': <reason>"), removing the temporary.
#pragma once
#include <string>

namespace lsi {

void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace lsi
