#include "fuzz_target.hpp"

#include <cstdio>
#include <cstdlib>

namespace lsi::fuzz {

void bug(const std::string& what) {
  std::fprintf(stderr, "lsi fuzz: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void check_error_message(const InputError& e) {
  const std::string m = e.what();
  static const bool verbose = std::getenv("LSI_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "rejected: %s\n", m.c_str());
  require(!m.empty(), "an InputError has an empty message");
  require(m.find('\n') == std::string::npos && m.find('\r') == std::string::npos,
          "an InputError message is not one line: " + m);
}

}  // namespace lsi::fuzz
