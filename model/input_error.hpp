// The error of every invalid input: `what()` is one line naming the field, its value and what is
// allowed, e.g. `landslide.thickness_m = -3: must be > 0 (m)`. The command line prints it and
// exits with code 2.
#pragma once
#include <stdexcept>

namespace lsi {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lsi
