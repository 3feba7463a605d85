// Order statistics of a column of values without sorting it: the values that would stand at a
// few given ranks of the column sorted ascending. A sweep's statistics need a dozen of them per
// output (the minimum and maximum, two values for each quantile and the bounds of its interval:
// sweeps/statistics.hpp); sorting millions of values to read a dozen takes a radix sort's eight
// passes over the whole column, selecting them two passes and a selection among few values.
//
// The values become 64-bit keys that compare as the values do (x >= +0: its bits with the sign
// bit set; x <= -0: its bits inverted), so -0 comes before +0 (std::sort leaves their order
// open) and every other value compares as with operator<. The column's values are counted by the
// top 16 bits of their keys (a histogram of 65536 buckets: the sign, the exponent and 4 bits of the
// mantissa, a sixteenth of an octave each); the buckets that hold a wanted rank are found from
// the counts; a second pass copies the keys of those buckets, each bucket into a region of its
// own; std::nth_element finds each rank in its region. A wanted bucket that holds one value only
// (a point mass of the distribution) is found by its least and greatest keys and gives that
// value without a copy. The values returned are bit for bit those of the sorted column, whatever
// the distribution: ties, infinities, point masses and a column of one value included.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace lsi::sweeps {

// The buffers of order_statistics, kept by a caller that selects from many columns.
struct OrderScratch {
  std::vector<std::uint64_t> keys;   // the wanted buckets' keys, plus one slot for the others
  std::vector<std::uint64_t> count;  // per bucket: values, then the first rank of the bucket
  std::vector<std::uint8_t> region;  // per bucket: 0, or 1 + the region of a wanted bucket
};

namespace detail {

inline std::uint64_t order_key(const double x) {
  constexpr std::uint64_t sign = std::uint64_t{1} << 63;
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return (u & sign) ? ~u : (u | sign);
}

inline double order_value(const std::uint64_t key) {
  constexpr std::uint64_t sign = std::uint64_t{1} << 63;
  const std::uint64_t u = (key & sign) ? (key & ~sign) : ~key;
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

// order_statistics by selection among all the values (few values, or many ranks).
inline void order_statistics_of_all(const double* const values, const std::size_t n,
                                    const std::size_t* const ranks, const std::size_t count,
                                    double* const out, std::vector<std::uint64_t>& keys) {
  keys.resize(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = order_key(values[i]);
  std::size_t from = 0;
  for (std::size_t j = 0; j < count; ++j) {
    const auto at = keys.begin() + std::ptrdiff_t(ranks[j]);
    std::nth_element(keys.begin() + std::ptrdiff_t(from), at, keys.end());
    out[j] = order_value(*at);
    from = ranks[j];
  }
}

}  // namespace detail

// out[j] = the value at rank ranks[j] (0-based) of values[0, n) sorted ascending, for the
// `count` ranks given in ascending order, each below n. No value may be NaN (the caller's check).
inline void order_statistics(const double* const values, const std::size_t n,
                             const std::size_t* const ranks, const std::size_t count,
                             double* const out, OrderScratch& s) {
  constexpr int shift = 48;
  constexpr std::size_t buckets = std::size_t{1} << (64 - shift), most = 255;
  if (n <= 4096 || count > most) {
    detail::order_statistics_of_all(values, n, ranks, count, out, s.keys);
    return;
  }
  // Pass 1: the values per bucket, then each bucket's first rank.
  s.count.assign(buckets + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++s.count[detail::order_key(values[i]) >> shift];
  std::uint64_t first = 0;
  for (std::size_t b = 0; b <= buckets; ++b) {
    const std::uint64_t c = s.count[b];
    s.count[b] = first;
    first += c;
  }
  // The wanted buckets (in ascending order, as the ranks), each a region of the keys.
  s.region.assign(buckets, 0);
  std::size_t wanted_bucket[most], region_start[most + 1], region_of_rank[most], regions = 0;
  bool large = false;  // a wanted bucket of more than a sixteenth of the values
  for (std::size_t j = 0; j < count; ++j) {
    // The last bucket whose first rank is at most the rank (it holds the rank: not empty).
    const auto after = std::upper_bound(s.count.begin(), s.count.begin() + std::ptrdiff_t(buckets),
                                        std::uint64_t(ranks[j]));
    const std::size_t b = std::size_t(after - s.count.begin()) - 1;
    if (regions == 0 || wanted_bucket[regions - 1] != b) {
      wanted_bucket[regions++] = b;
      large = large || std::size_t(s.count[b + 1] - s.count[b]) > n / 16;
    }
    region_of_rank[j] = regions - 1;
  }
  for (std::size_t r = 0; r < regions; ++r) s.region[wanted_bucket[r]] = std::uint8_t(r + 1);
  // A wanted bucket of a single value (a point mass, such as the zero final displacement of the
  // barriers that never slide) gives that value at each of its ranks without a copy of its keys.
  // Where a wanted bucket is large, a pass finds each one's least and greatest key (index 1 + the
  // region; 0 takes the other buckets' keys).
  std::uint64_t least[most + 1], greatest[most + 1];
  bool single[most] = {};
  if (large) {
    std::fill(least, least + regions + 1, ~std::uint64_t{0});
    std::fill(greatest, greatest + regions + 1, std::uint64_t{0});
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t k = detail::order_key(values[i]);
      const std::size_t r = s.region[k >> shift];
      least[r] = std::min(least[r], k);
      greatest[r] = std::max(greatest[r], k);
    }
    for (std::size_t r = 0; r < regions; ++r)
      if (least[r + 1] == greatest[r + 1]) {
        single[r] = true;
        s.region[wanted_bucket[r]] = 0;  // its keys go with the others'
      }
  }
  region_start[0] = 0;
  for (std::size_t r = 0; r < regions; ++r) {
    const std::size_t b = wanted_bucket[r];
    region_start[r + 1] =
        region_start[r] + (single[r] ? 0 : std::size_t(s.count[b + 1] - s.count[b]));
  }
  // Pass 2: each wanted bucket's keys into its region; the others all onto one slot past the
  // regions (a store either way, no branch).
  const std::size_t sink = region_start[regions];
  s.keys.resize(sink + 1);
  std::size_t next[most + 1];
  next[0] = sink;
  for (std::size_t r = 0; r < regions; ++r) next[r + 1] = region_start[r];
  std::uint64_t* const keys = s.keys.data();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = detail::order_key(values[i]);
    const std::size_t r = s.region[k >> shift];
    keys[next[r]] = k;
    next[r] += r != 0;
  }
  // Each rank within its region: nth_element from the previous rank of the same region on.
  std::size_t from = 0, previous_region = regions;
  for (std::size_t j = 0; j < count; ++j) {
    const std::size_t r = region_of_rank[j];
    if (single[r]) {
      out[j] = detail::order_value(least[r + 1]);
      continue;
    }
    const std::size_t at = region_start[r] + (ranks[j] - std::size_t(s.count[wanted_bucket[r]]));
    if (r != previous_region) from = region_start[r];
    std::nth_element(keys + from, keys + at, keys + region_start[r + 1]);
    out[j] = detail::order_value(keys[at]);
    from = at;
    previous_region = r;
  }
}

}  // namespace lsi::sweeps
