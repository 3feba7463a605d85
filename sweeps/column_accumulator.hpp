// The statistics of one output column whose values arrive a batch at a time, in sample order,
// without the column kept: describe() (sweeps/statistics.hpp) of all the values added, bit for
// bit, and the counts of values above given thresholds (the exceedance probabilities). A sweep
// of 1e7 samples then holds its chunk's rows and a few per cent of each column, not the table.
//
// * The counts, the least and greatest value and the sums of the mean and the standard deviation
//   (stats::LaneSum: the same terms in the same order as describe()'s, so the same sums) run as
//   the values arrive. The standard deviation's sums are taken about the mean of the first
//   values (stats::kShiftValues of them), which are kept until they are all in.
// * The quantiles and their intervals need a dozen order statistics, whose ranks are known only
//   at the end (they depend on the count). The first values, a random sample of the column in
//   a sweep's designs, locate each quantile: for q = 0.05, 0.5, 0.95 the range of keys between
//   the first values' order statistics at q -+ w, w = (z + 6) sqrt(q (1 - q) / m) + 4 / m (m of
//   them, z the normal quantile of the confidence), which holds the quantile and its interval's
//   bounds with a margin of six standard deviations of where m values put a quantile. From then
//   on every value below a range is counted, the values on a range's ends are counted, and those
//   inside are kept. At the end a wanted rank is found in the range whose counts cover it, and
//   selected among that range's values.
// * Where a rank lies outside every range (values that did not arrive in random order: a grid
//   walked in order), describe() asks its caller for the whole column once and describes that;
//   the result is the same, only slower.
// * Until the first values are all in (a column of fewer values), describe() is that of them.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sweeps/normal_distribution.hpp"
#include "sweeps/order_statistics.hpp"
#include "sweeps/statistics.hpp"

namespace lsi::sweeps {

class ColumnAccumulator {
 public:
  // thresholds: the values whose exceedances are counted; confidence: the intervals' (in (0,1));
  // first_values: how many values are kept whole before the ranges are set (at least 2).
  ColumnAccumulator(std::vector<double> thresholds, const double confidence,
                    const std::size_t first_values = stats::kShiftValues)
      : thresholds_(std::move(thresholds)),
        above_(thresholds_.size(), 0),
        confidence_(confidence),
        first_values_(std::max<std::size_t>(first_values, 2)) {
    stats::check_confidence(confidence);
  }

  // Adds n values, the next ones in sample order: a block of 2048 at a time, so that the passes
  // over a block read it from the first-level cache.
  void add(const double* const v, const std::size_t n) {
    constexpr std::size_t block = 2048;
    for (std::size_t i = 0; i < n; i += block) add_block(v + i, std::min(block, n - i));
  }

  std::size_t count() const { return count_; }
  // Values that are NaN or -inf (describe() refuses a column with any).
  std::size_t invalid_count() const { return invalid_; }
  // Values above thresholds[j].
  std::size_t above(const std::size_t j) const { return above_[j]; }
  // exceedance() of thresholds[j] (count() >= 1).
  ExceedanceEstimate exceedance(const std::size_t j) const {
    return exceedance_from_counts(thresholds_[j], above_[j], count_, confidence_);
  }

  // Whether describe() will ask for the whole column.
  bool needs_column() const {
    if (!ranged_ || count_ == 0) return false;
    const stats::DescribeRanks r = describe_ranks(count_, confidence_);
    for (std::size_t j = 0; j < r.count; ++j)
      if (r.rank[j] != 0 && r.rank[j] != count_ - 1 && !inner_rank(r.rank[j])) return true;
    return false;
  }

  // describe() of the values added; column() gives them all, in order, where needs_column().
  // Throws std::invalid_argument as describe() does (no values, a NaN or -inf among them).
  template <class Column>
  OutputStatistics describe(const Column& column, OrderScratch& scratch) {
    if (count_ == 0 || invalid_ > 0) {
      if (count_ == 0) throw std::invalid_argument("describe: no values (every sample failed?)");
      throw std::invalid_argument("describe: " + std::to_string(invalid_) +
                                  " values are NaN or -inf: each must be a number or +inf "
                                  "(exclude failed samples before the statistics)");
    }
    if (!ranged_) return sweeps::describe(first_, scratch, confidence_, first_values_);
    const std::size_t n = count_;
    const stats::DescribeRanks r = describe_ranks(n, confidence_);
    double at_rank[14];
    std::size_t from[3] = {0, 0, 0};
    for (std::size_t j = 0; j < r.count; ++j) {
      const std::size_t rank = r.rank[j];
      if (rank == 0) {
        at_rank[j] = detail::order_value(least_);
        continue;
      }
      if (rank == n - 1) {
        at_rank[j] = detail::order_value(greatest_);
        continue;
      }
      const auto found = inner_rank(rank);
      if (!found) return sweeps::describe(column(), scratch, confidence_, first_values_);
      Range& g = ranges_[found.range];
      std::size_t o = rank - g.below;
      if (o < g.at_lo) {
        at_rank[j] = detail::order_value(g.lo);
      } else if ((o -= g.at_lo) < g.inner.size()) {
        std::size_t& f = from[found.range];
        std::nth_element(g.inner.begin() + std::ptrdiff_t(f), g.inner.begin() + std::ptrdiff_t(o),
                         g.inner.end());
        at_rank[j] = detail::order_value(g.inner[o]);
        f = o;
      } else {
        at_rank[j] = detail::order_value(g.hi);
      }
    }
    stats::Moments m{stats::inf, stats::inf};
    if (infinite_ == 0) m = stats::moments_from_sums(n, sum_.total(), ss_.total(), c_.total());
    return describe_from(n, infinite_, m, r, at_rank, confidence_);
  }

  // The values kept in the ranges (the memory the accumulator holds beyond its first values).
  std::size_t values_kept() const {
    std::size_t kept = first_.size();
    for (const Range& g : ranges_) kept += g.inner.size();
    return kept;
  }

 private:
  // Keys in [lo, hi]: `below` the count of keys under lo, at_lo and at_hi the counts of keys
  // equal to lo and to hi (hi > lo), `inner` the keys between.
  struct Range {
    std::uint64_t lo, hi;
    std::size_t below = 0, at_lo = 0, at_hi = 0;
    std::vector<std::uint64_t> inner;
    std::size_t size() const { return at_lo + inner.size() + at_hi; }
  };
  struct Found {
    std::size_t range;
    bool ok;
    explicit operator bool() const { return ok; }
  };

  Found inner_rank(const std::size_t rank) const {
    for (std::size_t g = 0; g < ranges_.size(); ++g)
      if (rank >= ranges_[g].below && rank - ranges_[g].below < ranges_[g].size()) return {g, true};
    return {0, false};
  }

  // add() of one block.
  void add_block(const double* const v, const std::size_t n) {
    std::size_t invalid = 0, infinite = 0;
    std::uint64_t least = least_, greatest = greatest_;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = v[i];
      invalid += (x != x) | (x == -stats::inf);
      infinite += x == stats::inf;
      const std::uint64_t k = detail::order_key(x);
      least = std::min(least, k);
      greatest = std::max(greatest, k);
    }
    invalid_ += invalid;
    infinite_ += infinite;
    least_ = least;
    greatest_ = greatest;
    for (std::size_t j = 0; j < thresholds_.size(); ++j) {
      const double t = thresholds_[j];
      std::size_t above = 0;
      for (std::size_t i = 0; i < n; ++i) above += v[i] > t;
      above_[j] += above;
    }
    sum_.add_terms(n, [v](std::size_t i) { return v[i]; });
    count_ += n;
    std::size_t from = 0;
    if (!ranged_) {
      from = std::min(n, first_values_ - first_.size());
      first_.insert(first_.end(), v, v + from);
      if (first_.size() == first_values_) set_ranges();
    }
    if (ranged_ && from < n) take(v + from, n - from);
  }

  // The first values are in: the shift of the standard deviation's sums, the ranges; then the
  // first values are taken as any later ones and let go.
  void set_ranges() {
    const std::size_t m = first_.size();
    stats::LaneSum first;
    first.add_terms(m, [this](std::size_t i) { return first_[i]; });
    shift_ = first.total() / static_cast<double>(m);
    std::vector<std::uint64_t> keys(m);
    for (std::size_t i = 0; i < m; ++i) keys[i] = detail::order_key(first_[i]);
    const double z = normal_quantile(0.5 + 0.5 * confidence_);
    // The key at fraction p of the first values, rounded down (up: the rank above).
    const auto key_at = [&](const double p, const bool up) {
      const double at = std::clamp(p, 0.0, 1.0) * static_cast<double>(m - 1);
      const auto rank = static_cast<std::size_t>(up ? std::ceil(at) : std::floor(at));
      std::nth_element(keys.begin(), keys.begin() + std::ptrdiff_t(rank), keys.end());
      return keys[rank];
    };
    for (const double q : stats::DescribeRanks::q) {
      const double w = (z + 6.0) * std::sqrt(q * (1.0 - q) / static_cast<double>(m)) +
                       4.0 / static_cast<double>(m);
      Range g;
      g.lo = key_at(q - w, false);
      g.hi = key_at(q + w, true);
      if (!ranges_.empty() && g.lo <= ranges_.back().hi)
        ranges_.back().hi = std::max(ranges_.back().hi, g.hi);
      else
        ranges_.push_back(std::move(g));
    }
    ranged_ = true;
    take(first_.data(), m);
    std::vector<double>().swap(first_);
  }

  // Values after the first ones have set the ranges.
  void take(const double* const v, const std::size_t n) {
    const double k = shift_;
    ss_.add_terms(n, [v, k](std::size_t i) { return (v[i] - k) * (v[i] - k); });
    c_.add_terms(n, [v, k](std::size_t i) { return v[i] - k; });
    // Three ranges always (those missing hold no key: lo > hi), so that the passes have no inner
    // loop: the counts in one branch-free pass (vectorised), then, where a range holds keys, the
    // keys stored without a branch (each written at its range's end, which moves on only when
    // the key belongs to it) into room made for the number the first pass counted.
    std::uint64_t lo[3], hi[3];
    for (std::size_t g = 0; g < 3; ++g) {
      lo[g] = g < ranges_.size() ? ranges_[g].lo : ~std::uint64_t{0};
      hi[g] = g < ranges_.size() ? ranges_[g].hi : 0;
    }
    std::size_t below[3] = {0, 0, 0}, at_lo[3] = {0, 0, 0}, at_hi[3] = {0, 0, 0},
                inner[3] = {0, 0, 0};
    inside_.resize(n);  // whether each value lies inside a range, for the stores below
    unsigned char* const inside = inside_.data();
    {
      const std::uint64_t lo0 = lo[0], lo1 = lo[1], lo2 = lo[2];
      const std::uint64_t hi0 = hi[0], hi1 = hi[1], hi2 = hi[2];
      std::size_t b0 = 0, b1 = 0, b2 = 0, l0 = 0, l1 = 0, l2 = 0, h0 = 0, h1 = 0, h2 = 0, i0 = 0,
                  i1 = 0, i2 = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t key = detail::order_key(v[i]);
        b0 += key < lo0;
        b1 += key < lo1;
        b2 += key < lo2;
        l0 += key == lo0;
        l1 += key == lo1;
        l2 += key == lo2;
        h0 += key == hi0;
        h1 += key == hi1;
        h2 += key == hi2;
        const bool in0 = (key > lo0) & (key < hi0), in1 = (key > lo1) & (key < hi1),
                   in2 = (key > lo2) & (key < hi2);
        i0 += in0;
        i1 += in1;
        i2 += in2;
        inside[i] = static_cast<unsigned char>(in0 | in1 | in2);
      }
      const std::size_t b[3] = {b0, b1, b2}, l[3] = {l0, l1, l2}, h[3] = {h0, h1, h2},
                        k[3] = {i0, i1, i2};
      for (std::size_t g = 0; g < 3; ++g) {
        below[g] = b[g];
        at_lo[g] = l[g];
        at_hi[g] = h[g];
        inner[g] = k[g];
      }
    }
    std::uint64_t sink[1];
    std::uint64_t* to[3] = {sink, sink, sink};
    std::size_t was[3] = {0, 0, 0};
    bool any = false;
    for (std::size_t g = 0; g < ranges_.size(); ++g) {
      Range& r = ranges_[g];
      r.below += below[g];
      r.at_lo += at_lo[g];
      if (r.hi != r.lo) r.at_hi += at_hi[g];
      if (inner[g] == 0) continue;
      any = true;
      was[g] = r.inner.size();
      r.inner.resize(was[g] + inner[g] + 1);  // + 1: the last store of a key not kept
      to[g] = r.inner.data() + was[g];
    }
    if (!any) return;
    std::uint64_t* const to0 = to[0];
    std::uint64_t* const to1 = to[1];
    std::uint64_t* const to2 = to[2];
    std::size_t m0 = 0, m1 = 0, m2 = 0;
    const auto store = [&](const std::size_t i) {
      const std::uint64_t key = detail::order_key(v[i]);
      to0[m0] = key;
      m0 += (key > lo[0]) & (key < hi[0]);
      to1[m1] = key;
      m1 += (key > lo[1]) & (key < hi[1]);
      to2[m2] = key;
      m2 += (key > lo[2]) & (key < hi[2]);
    };
    // The stores of the groups of eight values that hold one inside a range (marked by the
    // counting pass): a few per cent of the values are kept, so most groups hold none, and the
    // stores, each waiting for the count before it, were the loop's cost.
    constexpr std::size_t G = 8;
    std::size_t i = 0;
    for (; i + G <= n; i += G) {
      std::uint64_t group;
      std::memcpy(&group, inside + i, G);
      if (group != 0)
        for (std::size_t j = i; j < i + G; ++j) store(j);
    }
    for (; i < n; ++i) store(i);
    for (std::size_t g = 0; g < ranges_.size(); ++g)
      if (inner[g] > 0) ranges_[g].inner.resize(was[g] + inner[g]);
  }

  std::vector<double> thresholds_;
  std::vector<std::size_t> above_;
  double confidence_;
  std::size_t first_values_, count_ = 0, invalid_ = 0, infinite_ = 0;
  std::uint64_t least_ = ~std::uint64_t{0}, greatest_ = 0;
  stats::LaneSum sum_, ss_, c_;
  double shift_ = 0.0;
  std::vector<double> first_;          // the first values, until first_values_ of them are in
  std::vector<Range> ranges_;          // ascending, disjoint
  std::vector<unsigned char> inside_;  // take()'s marks, kept from call to call
  bool ranged_ = false;
};

}  // namespace lsi::sweeps
