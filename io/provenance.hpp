// Where a result file comes from: the version and git revision of lsi that wrote it and the
// command line it was run with, stored as root attributes of every run and sweep file.
#pragma once
#include <hdf5.h>

#include <string>
#include <vector>

namespace lsi {

// Records the process's command line (main calls it first); a program that never calls it (a
// test, a library user) writes an empty one.
void set_command_line(int argc, const char* const* argv);
const std::vector<std::string>& command_line();
// The command line as one line a POSIX shell reads back into the same words.
std::string shell_quoted(const std::vector<std::string>& words);

// Writes the root attributes lsi_version, git_revision, command_line (shell_quoted) and argv
// (the words, an array of strings) to `file`.
void write_provenance(hid_t file);

}  // namespace lsi
