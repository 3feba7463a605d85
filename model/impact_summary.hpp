// The scalar outputs of a simulated impact, from its force history: the peak force (the largest
// mean over one output interval) and its time, the peak averaged over a longer window, the
// impact duration and the impulse delivered during it. The force samples are means over the
// interval that ends at each output time (the contact impulse divided by the interval), so the
// impulse up to any time is exact where the history is piecewise constant.
#pragma once
#include <vector>

namespace lsi {

// Largest mean of `force` over any window of length `window` (s) inside [time.front(),
// time.back()], with force[i] the mean over (time[i-1], time[i]]; and the time of that window's
// centre. A window at least as long as the history gives the mean over the whole history; a
// window shorter than every interval gives the largest sample.
struct WindowedPeak {
  double force = 0.0;  // N/m
  double time = 0.0;   // s, centre of the window
};
WindowedPeak windowed_peak(const std::vector<double>& time, const std::vector<double>& force,
                           double window);

// The impulse of `force` from time.front() to t (N s/m), interpolated within an interval.
double impulse_until(const std::vector<double>& time, const std::vector<double>& force, double t);

// Impact duration: the last time the force differs from its final value (the mean of the last
// 5 % of the samples: the static load of what the barrier retains) by more than 10 % of the peak;
// the time of the peak if it never does after it. Also the final value.
struct ImpactDuration {
  double duration = 0.0;     // s
  double final_force = 0.0;  // N/m
};
ImpactDuration impact_duration(const std::vector<double>& time, const std::vector<double>& force);

}  // namespace lsi
