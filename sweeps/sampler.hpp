// The sampler of `lsi sweep`: the uncertain inputs of sample i, drawn inside Kokkos kernels.
//
//   u in (0,1)^D from the design  ->  Gaussian copula (if a correlation is given)  ->  marginal quantiles
//
// Designs (one dimension per input, in the order of `inputs`; a Constant input still takes its
// dimension, so adding or removing an uncertain input never renumbers the others' streams):
//   MonteCarlo      u_d = uniform_open01(seed, i, d): Philox-4x32-10 keyed by the seed, counter =
//                   (sample, dimension) (counter_rng.hpp). Any index, any order.
//   LatinHypercube  u_d = (pi_d(i) + jitter) / N with pi_d a seed-keyed permutation of [0, N)
//                   evaluated without storing it (latin_hypercube.hpp); every stratum of every
//                   dimension is hit exactly once among samples 0..N-1. Indices >= N wrap (i mod N).
//   Sobol           Owen-scrambled (hash-based, keyed by the seed) Sobol points, Joe & Kuo direction
//                   numbers, 32 dimensions, 52-bit output precision (sobol.hpp). Any index; the
//                   balance properties hold for the first 2^m points, so choose N = 2^m.
//   Grid            the full factorial of each input's `values` (a Constant input without values
//                   counts as the single point `value`), the FIRST input varying fastest; the
//                   marginals are neither used nor validated (only the grid points, which must be
//                   finite); sample_count must be the product of the sizes.
//   Points          given points (a study's points file): sample i is row i of the table handed
//                   to the constructor, as given; no marginals, no copula. Indices < sample_count.
// Reproducibility: the uniforms of sample i depend only on (design, seed, i, N, the inputs' count);
// they are computed with integer arithmetic, so they are bitwise identical on every backend and for
// any batch, thread count or sharding. The transforms after them (copula, quantiles) are the same
// floating-point code on every host backend (bitwise identical between Serial and OpenMP, tested);
// on a GPU the math library (erfc, log, exp) may differ from the host's in the last bit.
//
// Correlation (Gaussian copula): z = L Phi^-1(u), with L the Cholesky factor (Eigen, on the host) of
// the given matrix R, then u'_d = Phi(z_d) and x_d = F_d^-1(u'_d); Normal and Lognormal marginals use
// z_d directly. R is therefore the correlation of the NORMAL SCORES Phi^-1(F_d(x_d)), not Pearson's
// correlation of the inputs: for two normal inputs they agree, for a lognormal or a discrete
// marginal Pearson's is smaller in magnitude (and bounded below 1). Dimensions whose row of L is
// that of the identity keep their uniform untouched (bitwise the same as without a correlation).
// With Latin hypercube or Sobol designs, the correlated dimensions lose the exact stratification of
// their marginals (the scores are stratified before L mixes them); the Grid design takes no
// correlation.
#pragma once
#include <Eigen/Dense>
#include <Kokkos_Core.hpp>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/common/math.hpp"
#include "sweeps/counter_rng.hpp"
#include "sweeps/distribution.hpp"
#include "sweeps/latin_hypercube.hpp"
#include "sweeps/normal_distribution.hpp"
#include "sweeps/sobol.hpp"

namespace lsi::sweeps {

enum class Design : int { MonteCarlo, LatinHypercube, Sobol, Grid, Points };

inline const char* to_string(Design d) {
  switch (d) {
    case Design::MonteCarlo:
      return "monte_carlo";
    case Design::LatinHypercube:
      return "latin_hypercube";
    case Design::Sobol:
      return "sobol";
    case Design::Grid:
      return "grid";
    case Design::Points:
      return "points";
  }
  return "unknown";
}

namespace detail {
// Checks the correlation matrix and returns its lower Cholesky factor, row-major (dims x dims);
// empty for "independent".
inline std::vector<double> cholesky_of_correlation(const std::vector<std::vector<double>>& r,
                                                   int dims) {
  if (r.empty()) return {};
  const auto n = static_cast<std::size_t>(dims);
  if (r.size() != n)
    invalid("correlation: " + std::to_string(r.size()) + " rows given for " + std::to_string(dims) +
            " inputs: must be a " + std::to_string(dims) + " x " + std::to_string(dims) +
            " matrix");
  for (std::size_t i = 0; i < n; ++i)
    if (r[i].size() != n)
      invalid("correlation[" + std::to_string(i) + "]: " + std::to_string(r[i].size()) +
              " entries given for " + std::to_string(dims) + " inputs: must be a " +
              std::to_string(dims) + " x " + std::to_string(dims) + " matrix");
  auto at = [](std::size_t i, std::size_t j) {
    return "correlation[" + std::to_string(i) + "][" + std::to_string(j) + "]";
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const double x = r[i][j];
      if (!std::isfinite(x)) invalid(at(i, j) + " = " + format_number(x) + ": must be finite");
      if (i == j && std::fabs(x - 1.0) > 1e-12)
        invalid(at(i, j) + " = " + format_number(x) +
                ": the diagonal of a correlation matrix must be 1");
      if (std::fabs(x) > 1.0) invalid(at(i, j) + " = " + format_number(x) + ": must be in [-1, 1]");
      if (std::fabs(x - r[j][i]) > 1e-12)
        invalid(at(i, j) + " = " + format_number(x) + " but " + at(j, i) + " = " +
                format_number(r[j][i]) + ": the correlation matrix must be symmetric");
    }
  Eigen::MatrixXd R(dims, dims);
  for (int i = 0; i < dims; ++i)
    for (int j = 0; j < dims; ++j) R(i, j) = 0.5 * (r[i][j] + r[j][i]);
  Eigen::LLT<Eigen::MatrixXd> llt(R);
  const double min_eigenvalue =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(R, Eigen::EigenvaluesOnly).eigenvalues()(0);
  if (llt.info() != Eigen::Success || !(min_eigenvalue > 1e-12))
    invalid(
        "correlation: not positive definite (smallest eigenvalue " + format_number(min_eigenvalue) +
        "): the correlations contradict each other (e.g. a ~ b, b ~ c strongly but a ~ c weakly), or "
        "some |rho| = 1; a valid correlation matrix has all eigenvalues > 0");
  const Eigen::MatrixXd L = llt.matrixL();
  std::vector<double> out(n * n, 0.0);
  for (int i = 0; i < dims; ++i)
    for (int j = 0; j <= i; ++j) out[static_cast<std::size_t>(i) * n + j] = L(i, j);
  return out;
}

template <class T, class MemorySpace>
Kokkos::View<T*, MemorySpace> to_view(const char* label, const std::vector<T>& v) {
  Kokkos::View<T*, MemorySpace> out(std::string(label), v.size());
  const Kokkos::View<const T*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> host(
      v.data(), v.size());
  Kokkos::deep_copy(out, host);
  return out;
}
}  // namespace detail

template <class MemorySpace>
class Sampler {
 public:
  static constexpr int max_dimensions = 32;

  // correlation: empty = independent, else a dims x dims symmetric positive-definite matrix with unit
  // diagonal (the Gaussian copula on the normal scores). Throws std::invalid_argument with a message
  // naming the problem: an invalid input ("input 2 (normal): sd = -1: must be > 0"), a non-PD /
  // non-symmetric / wrong-size matrix, |rho| > 1, more dimensions than max_dimensions (or than the
  // Sobol direction numbers shipped, the same 32), LatinHypercube with sample_count == 0, a Grid
  // input without grid points, a Grid sample_count that is not the product of the grid sizes, or a
  // correlation with the Grid design.
  Sampler(const std::vector<DistributionSpec>& inputs,
          const std::vector<std::vector<double>>& correlation, Design design, std::uint64_t seed,
          std::uint64_t sample_count)
      : design_(design), seed_(seed), count_(sample_count) {
    using detail::invalid;
    if (inputs.size() > static_cast<std::size_t>(max_dimensions))
      invalid(std::to_string(inputs.size()) + " uncertain inputs: at most " +
              std::to_string(max_dimensions) + " are supported" +
              (design == Design::Sobol ? " (the Sobol direction numbers shipped cover 32)" : ""));
    dims_ = static_cast<int>(inputs.size());
    if (design != Design::MonteCarlo && design != Design::LatinHypercube &&
        design != Design::Sobol && design != Design::Grid)
      invalid("design = " + std::to_string(static_cast<int>(design)) +
              ": not a design drawn from distributions" +
              (design == Design::Points ? " (given points take the points constructor)" : ""));

    std::vector<Marginal> marginals;
    std::vector<double> values, cdf;
    for (int d = 0; d < dims_; ++d) {
      try {
        // The Grid design uses only the grid points (`values`, checked below), not the marginals.
        marginals.push_back(design == Design::Grid ? Marginal{}
                                                   : prepare_marginal(inputs[d], values, cdf));
      } catch (const std::invalid_argument& e) {
        invalid("input " + std::to_string(d) + " (" + to_string(inputs[d].kind) + "): " + e.what());
      }
    }
    if (values.empty()) {  // Views of size 0 have no data(); keep one dummy entry
      values.push_back(0.0);
      cdf.push_back(1.0);
    }
    marginals_ = detail::to_view<Marginal, MemorySpace>("lsi::sweeps::marginals", marginals);
    discrete_values_ = detail::to_view<double, MemorySpace>("lsi::sweeps::discrete_values", values);
    discrete_cdf_ = detail::to_view<double, MemorySpace>("lsi::sweeps::discrete_cdf", cdf);

    if (design == Design::Grid && !correlation.empty())
      invalid(
          "correlation: not allowed with the Grid design (a full factorial has no joint distribution to "
          "correlate); remove it or choose another design");
    std::vector<double> L = detail::cholesky_of_correlation(correlation, dims_);
    correlated_mask_ = 0;
    for (int i = 0; i < dims_ && !L.empty(); ++i)
      for (int j = 0; j < i; ++j)
        if (L[static_cast<std::size_t>(i) * dims_ + j] != 0.0)
          correlated_mask_ |= std::uint32_t{1} << i;
    // The normal scores needed: those that L mixes into a correlated row (and, for free, those of
    // the Normal and Lognormal marginals, which use the score directly); the others are skipped.
    score_mask_ = 0;
    for (int i = 0; i < dims_ && correlated_mask_ != 0; ++i)
      if ((correlated_mask_ >> i) & 1u)
        for (int j = 0; j <= i; ++j)
          if (L[static_cast<std::size_t>(i) * dims_ + j] != 0.0)
            score_mask_ |= std::uint32_t{1} << j;
    if (correlated_mask_ != 0)
      for (int d = 0; d < dims_; ++d)
        if (marginals[d].kind == DistributionKind::Normal ||
            marginals[d].kind == DistributionKind::Lognormal)
          score_mask_ |= std::uint32_t{1} << d;
    if (correlated_mask_ == 0) L.assign(1, 1.0);
    cholesky_ = detail::to_view<double, MemorySpace>("lsi::sweeps::cholesky", L);

    for (int d = 0; d < max_dimensions; ++d) keys_[d] = 0;
    std::vector<std::uint64_t> directions(1, 0);
    std::vector<double> grid(1, 0.0);
    switch (design) {
      case Design::MonteCarlo:
      case Design::Points:  // refused above: given points take the points constructor
        break;
      case Design::LatinHypercube:
        if (sample_count == 0)
          invalid(
              "sample_count = 0: a Latin hypercube needs at least one sample (it stratifies [0,1) into "
              "sample_count intervals)");
        domain_ = make_permutation_domain(sample_count);
        for (int d = 0; d < dims_; ++d) keys_[d] = latin_hypercube_key(seed, d);
        break;
      case Design::Sobol:
        directions = sobol_direction_numbers(dims_);
        if (directions.empty()) directions.assign(1, 0);
        for (int d = 0; d < dims_; ++d) keys_[d] = sobol_scramble_seed(seed, d);
        break;
      case Design::Grid: {
        grid.clear();
        std::uint64_t product = 1;
        bool overflow = false;
        std::string sizes;
        for (int d = 0; d < dims_; ++d) {
          const DistributionSpec& s = inputs[d];
          std::vector<double> points = s.values;
          if (points.empty() && s.kind == DistributionKind::Constant) points.push_back(s.value);
          if (points.empty())
            invalid("input " + std::to_string(d) + " (" + to_string(s.kind) +
                    "): no grid points: the Grid design needs the input's `values`");
          for (std::size_t k = 0; k < points.size(); ++k)
            if (!std::isfinite(points[k]))
              invalid("input " + std::to_string(d) + " (" + to_string(s.kind) + "): values[" +
                      std::to_string(k) + "] = " + detail::format_number(points[k]) +
                      ": grid points must be finite");
          grid_offset_[d] = static_cast<std::uint32_t>(grid.size());
          grid_size_[d] = static_cast<std::uint32_t>(points.size());
          grid.insert(grid.end(), points.begin(), points.end());
          if (product > ~std::uint64_t{0} / points.size()) overflow = true;
          product *= points.size();
          sizes += (d ? " x " : "") + std::to_string(points.size());
        }
        if (overflow || product != sample_count)
          invalid("sample_count = " + std::to_string(sample_count) +
                  ": the Grid design's full factorial has " +
                  (overflow ? std::string("more than 2^64") : std::to_string(product)) +
                  " points (" + (sizes.empty() ? std::string("no inputs") : sizes) +
                  "); sample_count must equal it");
        if (grid.empty()) grid.push_back(0.0);
        break;
      }
    }
    sobol_directions_ =
        detail::to_view<std::uint64_t, MemorySpace>("lsi::sweeps::sobol_directions", directions);
    grid_values_ = detail::to_view<double, MemorySpace>("lsi::sweeps::grid_values", grid);
  }

  // The Points design: sample i is row i of `points`, a row-major table of sample_count rows of
  // `dims` values each. Throws std::invalid_argument for a table of another size, more
  // dimensions than max_dimensions, no rows, or a value that is not finite.
  Sampler(const std::vector<double>& points, int dims, std::uint64_t sample_count)
      : dims_(dims), design_(Design::Points), count_(sample_count) {
    using detail::invalid;
    if (dims < 1 || dims > max_dimensions)
      invalid(std::to_string(dims) + " columns of given points: 1 to " +
              std::to_string(max_dimensions) + " are supported");
    if (sample_count == 0) invalid("no given points: at least one row is needed");
    if (points.size() / static_cast<std::size_t>(dims) != sample_count ||
        points.size() % static_cast<std::size_t>(dims) != 0)
      invalid(std::to_string(points.size()) + " values given for " + std::to_string(sample_count) +
              " points of " + std::to_string(dims) + " values");
    for (std::size_t k = 0; k < points.size(); ++k)
      if (!std::isfinite(points[k]))
        invalid("point " + std::to_string(k / static_cast<std::size_t>(dims)) + ", value " +
                std::to_string(k % static_cast<std::size_t>(dims)) + " = " +
                detail::format_number(points[k]) + ": must be finite");
    // Column-major on the device: the threads of a kernel read one column side by side.
    points_ = Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>("lsi::sweeps::points",
                                                                      sample_count, dims);
    const auto host = Kokkos::create_mirror_view(points_);
    for (std::uint64_t i = 0; i < sample_count; ++i)
      for (int d = 0; d < dims; ++d) host(i, d) = points[i * static_cast<std::size_t>(dims) + d];
    Kokkos::deep_copy(points_, host);
    // The tables the other designs read stay valid (one dummy entry each).
    const std::vector<double> one(1, 1.0);
    marginals_ =
        detail::to_view<Marginal, MemorySpace>("lsi::sweeps::marginals", std::vector<Marginal>(1));
    discrete_values_ = detail::to_view<double, MemorySpace>("lsi::sweeps::discrete_values", one);
    discrete_cdf_ = detail::to_view<double, MemorySpace>("lsi::sweeps::discrete_cdf", one);
    cholesky_ = detail::to_view<double, MemorySpace>("lsi::sweeps::cholesky", one);
    grid_values_ = detail::to_view<double, MemorySpace>("lsi::sweeps::grid_values", one);
    sobol_directions_ = detail::to_view<std::uint64_t, MemorySpace>(
        "lsi::sweeps::sobol_directions", std::vector<std::uint64_t>(1, 0));
  }

  int dimensions() const { return dims_; }
  std::uint64_t sample_count() const { return count_; }
  Design design() const { return design_; }
  std::uint64_t seed() const { return seed_; }
  bool correlated() const { return correlated_mask_ != 0; }

  // The uniforms of sample `index` before the copula (what the design draws), u[0..dimensions()).
  // For the Grid design: the grid indices (as doubles) instead; for Points: the point itself.
  KOKKOS_INLINE_FUNCTION void design_uniforms(std::uint64_t index, double* u) const {
    switch (design_) {
      case Design::MonteCarlo:
        for (int d = 0; d < dims_; ++d)
          u[d] = uniform_open01(seed_, index, static_cast<std::uint32_t>(d));
        break;
      case Design::LatinHypercube:
        for (int d = 0; d < dims_; ++d)
          u[d] = latin_hypercube_uniform(seed_, keys_[d], domain_, index, d);
        break;
      case Design::Sobol:
        for (int d = 0; d < dims_; ++d)
          u[d] = sobol_word_to_open01(
              owen_scramble64(sobol_word(&sobol_directions_(d * sobol_bits), index), keys_[d]));
        break;
      case Design::Grid: {
        std::uint64_t r = count_ > 0 ? index % count_ : 0;
        for (int d = 0; d < dims_; ++d) {
          u[d] = static_cast<double>(r % grid_size_[d]);
          r /= grid_size_[d];
        }
        break;
      }
      case Design::Points:
        for (int d = 0; d < dims_; ++d) u[d] = points_(index, d);
        break;
    }
  }

  // Fills out[0..dimensions()) with the inputs of sample `index` (any index < sample_count; for
  // MonteCarlo and Sobol any index at all). Device-callable; the object is cheap to copy into a lambda.
  KOKKOS_INLINE_FUNCTION void sample(std::uint64_t index, double* out) const {
    if (design_ == Design::Points) {
      for (int d = 0; d < dims_; ++d) out[d] = points_(index, d);
      return;
    }
    double u[max_dimensions];
    design_uniforms(index, u);
    if (design_ == Design::Grid) {
      for (int d = 0; d < dims_; ++d)
        out[d] = grid_values_(grid_offset_[d] + static_cast<std::uint32_t>(u[d]));
      return;
    }
    const double* values = discrete_values_.data();
    const double* cdf = discrete_cdf_.data();
    if (correlated_mask_ == 0) {
      for (int d = 0; d < dims_; ++d)
        out[d] = marginal_quantile(marginals_(d), u[d], 0.0, false, values, cdf);
      return;
    }
    double z[max_dimensions];
    for (int d = 0; d < dims_; ++d) z[d] = ((score_mask_ >> d) & 1u) ? normal_quantile(u[d]) : 0.0;
    // z <- L z in place, from the last row up (row d reads z[0..d], not yet overwritten); each
    // term a fused multiply-add written out, so that sample_block's rows round alike.
    for (int d = dims_ - 1; d >= 0; --d) {
      if (!((correlated_mask_ >> d) & 1u)) continue;
      double s = 0.0;
      for (int k = 0; k <= d; ++k) s = math::fused_multiply_add(cholesky_(d * dims_ + k), z[k], s);
      z[d] = s;
      u[d] = normal_cdf(s);
    }
    for (int d = 0; d < dims_; ++d)
      out[d] = marginal_quantile(marginals_(d), u[d], z[d], (score_mask_ >> d) & 1u, values, cdf);
  }

  // Samples per call of sample_block.
  static constexpr int block_size = 64;

  // Host code: the inputs of samples first .. first + block_size - 1 into
  // out[d * block_size + k] (input d of sample first + k), the same bits as sample(first + k).
  // sample() runs every stage for one sample; this runs each stage for the whole block, in loops
  // that GCC vectorises: the Monte Carlo uniforms (Philox), Phi^-1 (normal_quantile_each), the
  // Cholesky rows and the marginals' arithmetic (marginal_quantile_each). What stays a call per
  // value is the same scalar code: the logarithms of Phi^-1's tails, erfc, exp, a long discrete
  // table's search, and the other designs' uniforms (the Grid and Points designs run sample()
  // for each).
  void sample_block(std::uint64_t first, double* out) const {
    constexpr int B = block_size;
    if (design_ == Design::Points || design_ == Design::Grid) {
      double x[max_dimensions];
      for (int k = 0; k < B; ++k) {
        sample(first + k, x);
        for (int d = 0; d < dims_; ++d) out[d * B + k] = x[d];
      }
      return;
    }
    double* u = out;  // the uniforms, then the inputs in their place
    if (design_ == Design::MonteCarlo) {
      for (int d = 0; d < dims_; ++d)
        uniform_open01_each(seed_, first, static_cast<std::uint32_t>(d), u + d * B, B);
    } else {
      double v[max_dimensions];
      for (int k = 0; k < B; ++k) {
        design_uniforms(first + k, v);
        for (int d = 0; d < dims_; ++d) u[d * B + k] = v[d];
      }
    }
    const double* values = discrete_values_.data();
    const double* cdf = discrete_cdf_.data();
    double z[max_dimensions * B];
    if (correlated_mask_ != 0) {
      for (int d = 0; d < dims_; ++d) {
        if ((score_mask_ >> d) & 1u) {
          normal_quantile_each(u + d * B, z + d * B, B);
        } else {
          for (int k = 0; k < B; ++k) z[d * B + k] = 0.0;
        }
      }
      // z <- L z, from the last row up, as in sample().
      for (int d = dims_ - 1; d >= 0; --d) {
        if (!((correlated_mask_ >> d) & 1u)) continue;
        double s[B];
        for (int k = 0; k < B; ++k) s[k] = 0.0;
        for (int j = 0; j <= d; ++j) {
          const double c = cholesky_(d * dims_ + j);
          const double* zj = z + j * B;
#pragma GCC ivdep
          for (int k = 0; k < B; ++k) s[k] = math::fused_multiply_add(c, zj[k], s[k]);
        }
        for (int k = 0; k < B; ++k) {
          z[d * B + k] = s[k];
          u[d * B + k] = normal_cdf(s[k]);
        }
      }
    }
    for (int d = 0; d < dims_; ++d)
      marginal_quantile_each(marginals_(d), u + d * B, z + d * B, (score_mask_ >> d) & 1u, values,
                             cdf, out + d * B, B);
  }

 private:
  int dims_ = 0;
  Design design_ = Design::MonteCarlo;
  std::uint64_t seed_ = 0, count_ = 0;
  std::uint32_t correlated_mask_ = 0;  // bit d: row d of L mixes other dimensions in
  std::uint32_t score_mask_ = 0;       // bit d: the copula computes the normal score of dimension d
  PermutationDomain domain_{};
  std::uint64_t keys_[max_dimensions] =
      {};  // Latin hypercube permutation keys / Sobol scrambling seeds
  std::uint32_t grid_offset_[max_dimensions] = {}, grid_size_[max_dimensions] = {};
  Kokkos::View<Marginal*, MemorySpace> marginals_;
  Kokkos::View<double*, MemorySpace> discrete_values_, discrete_cdf_, cholesky_, grid_values_;
  Kokkos::View<std::uint64_t*, MemorySpace> sobol_directions_;
  Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace> points_;  // Points: sample x input
};

// On a host execution space: each_block(i0, count, x) for the blocks of samples [i0, i0 + count)
// of [0, n), with x[d * block_size + k] the inputs of sample first + i0 + k (k < count): a whole
// block drawn by Sampler::sample_block, the last, partial block one sample at a time
// (Sampler::sample) into the same layout; the blocks in parallel on `space`. For the callers
// whose work over a block's samples is itself a loop the compiler vectorises.
template <class ExecSpace, class MemorySpace, class EachBlock>
void draw_sample_blocks_on_host(const ExecSpace& space, const Sampler<MemorySpace>& s,
                                std::uint64_t first, std::size_t n, const EachBlock& each_block) {
  static_assert(Kokkos::SpaceAccessibility<ExecSpace, Kokkos::HostSpace>::accessible,
                "draw_sample_blocks_on_host: sample_block is host code");
  constexpr int B = Sampler<MemorySpace>::block_size;
  constexpr int capacity = Sampler<MemorySpace>::max_dimensions * B;
  const Sampler<MemorySpace> sampler = s;
  const int dims = s.dimensions();
  Kokkos::parallel_for("lsi::sweeps::draw_sample_blocks",
                       Kokkos::RangePolicy<ExecSpace>(space, 0, (n + B - 1) / B),
                       [=](const std::size_t block) {
                         const std::size_t begin = block * B;
                         alignas(64) double x[capacity];
                         int count = B;
                         if (begin + B <= n) {
                           sampler.sample_block(first + begin, x);
                         } else {
                           count = static_cast<int>(n - begin);
                           for (int k = 0; k < count; ++k) {
                             double one[Sampler<MemorySpace>::max_dimensions];
                             sampler.sample(first + begin + k, one);
                             for (int d = 0; d < dims; ++d) x[d * B + k] = one[d];
                           }
                         }
                         each_block(begin, count, static_cast<const double*>(x));
                       });
}

// On a host execution space: each(scratch, i, x, stride) for the samples i in [0, n), with
// x[d * stride] the inputs of sample first + i, a block at a time (draw_sample_blocks_on_host).
// `scratch` is a copy of `scratch0` made once a block, for state that each() sets anew for every
// sample: copied once a block rather than once a sample.
template <class ExecSpace, class MemorySpace, class Scratch, class Each>
void draw_blocks_on_host(const ExecSpace& space, const Sampler<MemorySpace>& s, std::uint64_t first,
                         std::size_t n, const Scratch& scratch0, const Each& each) {
  constexpr int B = Sampler<MemorySpace>::block_size;
  draw_sample_blocks_on_host(space, s, first, n,
                             [=](const std::size_t i0, const int count, const double* x) {
                               Scratch scratch = scratch0;
                               for (int k = 0; k < count; ++k) each(scratch, i0 + k, x + k, B);
                             });
}

// The same without a scratch: each(i, x, stride).
template <class ExecSpace, class MemorySpace, class Each>
void draw_blocks_on_host(const ExecSpace& space, const Sampler<MemorySpace>& s, std::uint64_t first,
                         std::size_t n, const Each& each) {
  struct None {};
  draw_blocks_on_host(
      space, s, first, n, None{},
      [=](None&, const std::size_t i, const double* x, const int stride) { each(i, x, stride); });
}

// Fills out(i, d) = inputs of sample first + i, in one parallel_for on `space`. out must have
// dimensions() columns (throws std::invalid_argument otherwise).
template <class ExecSpace, class MemorySpace>
void sample_batch(const ExecSpace& space, const Sampler<MemorySpace>& s, std::uint64_t first,
                  const Kokkos::View<double**, Kokkos::LayoutLeft, MemorySpace>& out) {
  static_assert(Kokkos::SpaceAccessibility<ExecSpace, MemorySpace>::accessible,
                "sample_batch: the execution space cannot read the sampler's memory (a host "
                "sampler drawn on a device)");
  if (out.extent(1) != static_cast<std::size_t>(s.dimensions()))
    throw std::invalid_argument("sample_batch: the output has " + std::to_string(out.extent(1)) +
                                " columns for " + std::to_string(s.dimensions()) + " inputs");
  const Sampler<MemorySpace> sampler = s;
  const auto o = out;
  const int dims = s.dimensions();
  if constexpr (Kokkos::SpaceAccessibility<ExecSpace, Kokkos::HostSpace>::accessible) {
    // On the host a block of samples at a time.
    draw_blocks_on_host(space, s, first, out.extent(0),
                        [=](const std::size_t i, const double* x, const int stride) {
                          for (int d = 0; d < dims; ++d) o(i, d) = x[d * stride];
                        });
  } else {
    Kokkos::parallel_for(
        "lsi::sweeps::sample_batch",
        Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<std::int64_t>>(
            space, 0, static_cast<std::int64_t>(out.extent(0))),
        KOKKOS_LAMBDA(const std::int64_t i) {
          double x[Sampler<MemorySpace>::max_dimensions];
          sampler.sample(first + static_cast<std::uint64_t>(i), x);
          for (int d = 0; d < dims; ++d) o(i, d) = x[d];
        });
  }
}

}  // namespace lsi::sweeps
