// The dam-break validation cases (scenes/verification/dam-break-*.json) and their experiments
// (scenes/verification/data/): shared by the test and the report that writes the figures.
#pragma once
#include <string>
#include <vector>

#include "model/method_result.hpp"

namespace lsi::test {

// Martin & Moyce (1952), n^2 = 2: T = t (2 g / a)^(1/2), Z = x / a.
struct SurgeFrontPoint {
  double a, T, Z;
};
std::vector<SurgeFrontPoint> martin_moyce_front(const std::string& csv);

// Lobovsky et al. (2014), H = 300 mm, one event: t* = t (g / H)^(1/2), p / (rho g H) per sensor.
struct WallPressureRecord {
  std::vector<double> t_star;
  std::vector<double> sensor[4];  // 3, 15, 30, 80 mm above the bottom
};
WallPressureRecord lobovsky_wall_pressure(const std::string& csv);

// The MPM's surge front Z (x from the wall over a) at the outputs: the farthest point's centre
// plus half a point's spacing (its share of the material), less the wall's position.
std::vector<double> mpm_front_z(const MethodResult& r, double wall_x, double a,
                                double point_spacing);

// The first peak of a pressure history after it first exceeds `onset`: its value and time (the
// largest value within `window` after the onset). {0, -1} if it never does.
struct Peak {
  double value, time;
};
Peak first_peak(const std::vector<double>& t, const std::vector<double>& p, double onset,
                double window);

// The mean of y over a window of length w centred on each sample (a moving average), for
// comparing a sampled record with an output averaged over an interval w.
std::vector<double> moving_average(const std::vector<double>& t, const std::vector<double>& y,
                                   double w);

// Linear interpolation of (x, y) at xq (x increasing; clamped at the ends).
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq);

}  // namespace lsi::test
