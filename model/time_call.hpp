// Wall time of one call of a fast function (a closed-form method: microseconds), in seconds: the
// call is repeated for at least 20 ms (and at least 3 times) so that it is measured well above the
// clock's resolution, and the mean is returned. `out` receives the last result.
#pragma once
#include <chrono>

namespace lsi {

template <class F, class Result>
double time_call(F&& f, Result& out) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  int reps = 0;
  double elapsed = 0.0;
  do {
    out = f();
    ++reps;
    elapsed = std::chrono::duration<double>(clock::now() - start).count();
  } while (reps < 3 || (elapsed < 0.02 && reps < 100000));
  return elapsed / reps;
}

}  // namespace lsi
