// Runs a shell command and returns its exit code and standard output: how the end-to-end tests
// run the `lsi` executable (redirect stderr in the command, e.g. "2>&1", to capture it too).
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace lsi::testing {

struct CommandOutcome {
  int code;          // exit code, -1 if the command did not exit normally
  std::string out;   // what it wrote on standard output
};

inline CommandOutcome run_command(const std::string& command) {
  FILE* p = popen(command.c_str(), "r");
  if (!p) return {-1, "popen failed"};
  std::string out;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace lsi::testing
