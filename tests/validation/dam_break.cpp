#include "dam_break.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lsi::test {
namespace {
// The numeric rows of a CSV whose comment lines start with '#' and whose first other line is
// the header.
std::vector<std::vector<double>> csv_rows(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::vector<double>> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::vector<double> row;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}
}  // namespace

std::vector<SurgeFrontPoint> martin_moyce_front(const std::string& csv) {
  std::vector<SurgeFrontPoint> points;
  for (const auto& r : csv_rows(csv)) points.push_back({r.at(0), r.at(1), r.at(2)});
  return points;
}

WallPressureRecord lobovsky_wall_pressure(const std::string& csv) {
  WallPressureRecord rec;
  for (const auto& r : csv_rows(csv)) {
    rec.t_star.push_back(r.at(0));
    for (int k = 0; k < 4; ++k) rec.sensor[k].push_back(r.at(1 + k));
  }
  return rec;
}

std::vector<double> mpm_front_z(const MethodResult& r, double wall_x, double a,
                                double point_spacing) {
  std::vector<double> z;
  for (double x : r.series.at("front_x").values)
    z.push_back((x + 0.5 * point_spacing - wall_x) / a);
  return z;
}

Peak first_peak(const std::vector<double>& t, const std::vector<double>& p, double onset,
                double window) {
  std::size_t i = 0;
  while (i < p.size() && !(p[i] > onset)) ++i;
  if (i == p.size()) return {0.0, -1.0};
  Peak best{p[i], t[i]};
  for (std::size_t j = i; j < p.size() && t[j] <= t[i] + window; ++j)
    if (p[j] > best.value) best = {p[j], t[j]};
  return best;
}

std::vector<double> moving_average(const std::vector<double>& t, const std::vector<double>& y,
                                   double w) {
  std::vector<double> out(y.size());
  std::size_t lo = 0, hi = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    while (hi < y.size() && t[hi] <= t[i] + 0.5 * w) sum += y[hi++];
    while (t[lo] < t[i] - 0.5 * w) sum -= y[lo++];
    out[i] = sum / double(hi - lo);
  }
  return out;
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  if (xq <= x.front()) return y.front();
  if (xq >= x.back()) return y.back();
  const std::size_t i = std::upper_bound(x.begin(), x.end(), xq) - x.begin();
  const double f = (xq - x[i - 1]) / (x[i] - x[i - 1]);
  return y[i - 1] + f * (y[i] - y[i - 1]);
}

}  // namespace lsi::test
