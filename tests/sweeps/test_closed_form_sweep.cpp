// The sweep's closed-form kernel (sweeps/closed_form_sweep.hpp): its checks of only what sampling
// changes give the first invalid field of the full check, and its batched models give, bit for
// bit, the scalar models' outputs of every sample (NaN for an invalid one), on every backend.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "sweeps/closed_form_sweep.hpp"
#include "tests/support/backends.hpp"

namespace {

namespace sw = lsi::sweeps;

// A valid scene (a front-body-tail landslide, a barrier given by its density, a vertical face).
sw::SceneValues valid_base() {
  sw::SceneValues s;
  double* v = s.value;
  v[sw::thickness_m] = 2.0;
  v[sw::velocity_m_s] = 6.0;
  v[sw::density_kg_m3] = 1800.0;
  v[sw::body_squares] = 6.0;
  v[sw::length_m] = 10.0;
  v[sw::flow_base_friction] = 0.3;
  v[sw::porosity] = 0.4;
  v[sw::friction_angle_deg] = 30.0;
  v[sw::cohesion_kpa] = 0.0;
  v[sw::young_modulus_mpa] = 10.0;
  v[sw::poisson_ratio] = 0.3;
  v[sw::hydraulic_conductivity_m_s] = 1e-4;
  v[sw::liquid_bulk_modulus_mpa] = 100.0;
  v[sw::liquid_viscosity_kpa_s] = 1e-6;
  v[sw::height_m] = 4.0;
  v[sw::base_width_m] = 3.0;
  v[sw::top_width_m] = 1.0;
  v[sw::face_angle_deg] = 90.0;
  v[sw::barrier_density_kg_m3] = 2400.0;
  v[sw::barrier_mass_kg_per_m] = 1e4;
  v[sw::base_friction] = 0.5;
  v[sw::face_friction] = 0.2;
  v[sw::empirical_a1] = 1.781;
  v[sw::empirical_a2] = -0.515;
  v[sw::empirical_tau] = 0.14;
  v[sw::empirical_kappa] = 0.0;
  v[sw::analytical_lambda] = 0.41;
  v[sw::analytical_tau] = 0.25;
  return s;
}

// A value for a field: mostly plausible ones, often at or beyond a range's ends.
double some_value(std::mt19937_64& g) {
  static const double special[] = {0.0, -1.0, 0.5, 1.0, 1.5, 2.5, 45.0, 89.0, 90.0, 91.0, 1e6 + 1};
  std::uniform_int_distribution<int> pick(0, 2);
  if (pick(g) == 0) return special[std::uniform_int_distribution<int>(0, 10)(g)];
  return std::uniform_real_distribution<double>(-0.5, 8.0)(g);
}

TEST(SampleChecks, GiveTheFirstInvalidFieldOfTheFullCheck) {
  std::mt19937_64 g(7);
  int invalid = 0, trials = 0;
  for (int variant = 0; variant < 6; ++variant) {
    sw::SceneValues base = valid_base();
    base.rectangle = variant == 1;
    base.barrier_given_by_mass = variant == 2;
    base.empirical_momentum = variant == 3;
    if (variant == 4) base.value[sw::face_angle_deg] = 70.0;      // a face that must fit
    if (variant == 5) base.value[sw::porosity] = 1.5;             // an invalid base scene
    ASSERT_EQ(sw::first_invalid_field(base) >= 0, variant == 5);  // the base as intended
    for (int trial = 0; trial < 3000; ++trial, ++trials) {
      int targets[5];
      const int n = std::uniform_int_distribution<int>(1, 5)(g);
      for (int d = 0; d < n; ++d)
        targets[d] = std::uniform_int_distribution<int>(-1, sw::scene_field_count - 1)(g);
      const sw::SampleChecks checks = sw::sample_checks(base, targets, n);
      sw::SceneValues s = base;
      for (int d = 0; d < n; ++d)
        if (targets[d] >= 0) s.value[targets[d]] = some_value(g);
      const int expected = sw::first_invalid_field(s);
      invalid += expected >= 0;
      ASSERT_EQ(sw::first_invalid_field(s, checks), expected)
          << "variant " << variant << ", trial " << trial;
    }
  }
  // Both outcomes were exercised (a third to two thirds of the samples are invalid).
  EXPECT_GT(invalid, trials / 5);
  EXPECT_LT(invalid, trials - trials / 5);
}

template <class Exec>
class ClosedFormSweepKernel : public ::testing::Test {};
TYPED_TEST_SUITE(ClosedFormSweepKernel, lsi::test::Backends);

// Runs the kernel on given points and compares each sample's outputs with the scalar models.
template <class Exec>
void expect_scalar_outputs(const sw::SceneValues& base, const std::vector<int>& targets,
                           const std::vector<double>& points, std::size_t n) {
  using Mem = typename Exec::memory_space;
  const int dims = static_cast<int>(targets.size());
  sw::ClosedFormSweep<Mem> sweep(sw::Sampler<Mem>(points, dims, n));
  sweep.base = base;
  for (int d = 0; d < dims; ++d) sweep.target[d] = targets[static_cast<std::size_t>(d)];
  sweep.empirical = sweep.analytical = true;
  const int columns = 2 * sw::closed_form_output_count;
  Kokkos::View<double**, Kokkos::LayoutLeft, Mem> in("in", n, dims), out("out", n, columns);
  Kokkos::View<int*, Mem> bad("bad", n);
  sw::ClosedFormChunkColumns<Mem> kept;
  // Twice with the same columns: a chunk that reuses them gives the same outputs.
  for (int pass = 0; pass < 2; ++pass) {
    sw::evaluate_closed_form_chunk(Exec(), sweep, 0, in, out, bad, kept);
    Exec().fence();
    const auto h_out = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
    const auto h_bad = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), bad);
    int invalid = 0;
    for (std::size_t i = 0; i < n; ++i) {
      sw::SceneValues s = base;
      for (int d = 0; d < dims; ++d) s.value[targets[d]] = points[i * dims + d];
      const int expected_bad = sw::first_invalid_field(s);
      ASSERT_EQ(h_bad(i), expected_bad) << "sample " << i;
      invalid += expected_bad >= 0;
      double e[sw::closed_form_output_count], a[sw::closed_form_output_count];
      if (expected_bad < 0) {
        sw::evaluate_empirical(s, e);
        sw::evaluate_analytical(s, a);
      }
      for (int o = 0; o < sw::closed_form_output_count; ++o) {
        const double want[2] = {expected_bad < 0 ? e[o] : NAN, expected_bad < 0 ? a[o] : NAN};
        for (int m = 0; m < 2; ++m) {
          const double got = h_out(i, m * sw::closed_form_output_count + o);
          if (std::isnan(want[m]))
            EXPECT_TRUE(std::isnan(got)) << "sample " << i << ", column " << o;
          else
            EXPECT_EQ(std::memcmp(&got, &want[m], sizeof got), 0)
                << "sample " << i << ", method " << m << ", output " << o << ": " << got
                << " against " << want[m];
        }
      }
    }
    EXPECT_GT(invalid, 0);
    EXPECT_LT(invalid, static_cast<int>(n) / 5);
  }
}

// Points of these fields: plausible values, one sample in 25 with a negative thickness.
std::vector<double> points_of(const std::vector<int>& targets, std::size_t n, unsigned seed) {
  std::mt19937_64 g(seed);
  std::vector<double> p;
  for (std::size_t i = 0; i < n; ++i)
    for (int f : targets) {
      std::uniform_real_distribution<double> u(0.0, 1.0);
      double v = 0.0;
      switch (f) {
        case sw::thickness_m:
          v = i % 25 == 3 ? -1.0 : 0.5 + 3.0 * u(g);
          break;
        case sw::velocity_m_s:
          v = 1.0 + 14.0 * u(g);
          break;
        case sw::face_angle_deg:
          v = 60.0 + 30.0 * u(g);
          break;
        case sw::barrier_density_kg_m3:
          v = 2200.0 + 400.0 * u(g);
          break;
        case sw::base_friction:
          v = 0.2 + 0.6 * u(g);
          break;
        case sw::empirical_a1:
          v = 1.0 + u(g);
          break;
        case sw::analytical_tau:
          v = 0.1 + 0.5 * u(g);
          break;
        case sw::body_squares:  // an integer, but one sample in 31 (an invalid one)
          v = i % 31 == 5 ? 4.5 : double(4 + i % 5);
          break;
        default:
          v = 1.0;
      }
      p.push_back(v);
    }
  return p;
}

TYPED_TEST(ClosedFormSweepKernel, DrawsTheSamplersSamples) {
  // A Monte Carlo design through the copula, 1037 samples from index 100 (neither end on a block
  // of the host's draw): each sample's inputs in `inputs` and its validity in `invalid_field`
  // are those of Sampler::sample(100 + i), bit for bit on the host (a device's math library may
  // round the quantiles differently in the last bit: 1e-13 relative there).
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  sw::DistributionSpec thickness, velocity, friction;
  thickness.kind = sw::DistributionKind::Lognormal;
  thickness.mean = 2.0;
  thickness.sd = 0.6;
  velocity.kind = sw::DistributionKind::TruncatedNormal;
  velocity.mean = 6.0;
  velocity.sd = 3.0;
  velocity.min = -1.0;  // some samples invalid (velocity must be > 0)
  velocity.max = 15.0;
  friction.kind = sw::DistributionKind::Uniform;
  friction.min = 0.2;
  friction.max = 0.8;
  const std::vector<sw::DistributionSpec> specs = {thickness, velocity, friction};
  const std::vector<std::vector<double>> rho = {{1, 0.4, 0}, {0.4, 1, 0.2}, {0, 0.2, 1}};
  const std::size_t n = 1037, first = 100;
  sw::ClosedFormSweep<Mem> sweep(
      sw::Sampler<Mem>(specs, rho, sw::Design::MonteCarlo, 2022, first + n));
  const sw::Sampler<Kokkos::HostSpace> host(specs, rho, sw::Design::MonteCarlo, 2022, first + n);
  sweep.base = valid_base();
  sweep.target[0] = sw::thickness_m;
  sweep.target[1] = sw::velocity_m_s;
  sweep.target[2] = sw::base_friction;
  sweep.empirical = sweep.analytical = true;
  Kokkos::View<double**, Kokkos::LayoutLeft, Mem> in("in", n, 3),
      out("out", n, 2 * sw::closed_form_output_count);
  Kokkos::View<int*, Mem> bad("bad", n);
  sw::evaluate_closed_form_chunk(Exec(), sweep, first, in, out, bad);
  Exec().fence();
  const auto h_in = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), in);
  const auto h_bad = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), bad);
  constexpr bool bitwise = Kokkos::SpaceAccessibility<Exec, Kokkos::HostSpace>::accessible;
  int invalid = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double x[3];
    host.sample(first + i, x);
    sw::SceneValues s = valid_base();
    for (int d = 0; d < 3; ++d) {
      if (bitwise)
        ASSERT_EQ(h_in(i, d), x[d]) << "sample " << first + i << ", input " << d;
      else
        ASSERT_NEAR(h_in(i, d), x[d], 1e-13 * std::fabs(x[d])) << "sample " << first + i;
      s.value[sweep.target[d]] = h_in(i, d);
    }
    ASSERT_EQ(h_bad(i), sw::first_invalid_field(s)) << "sample " << first + i;
    invalid += h_bad(i) >= 0;
  }
  EXPECT_GT(invalid, 0);  // both outcomes exercised
  EXPECT_LT(invalid, static_cast<int>(n) / 2);
}

TYPED_TEST(ClosedFormSweepKernel, BatchedModelsGiveTheScalarModelsOutputs) {
  // 1000 + 37 samples: whole blocks of the batches and a partial last one.
  const std::size_t n = 1037;
  const std::vector<int> targets = {sw::thickness_m,    sw::velocity_m_s,
                                    sw::face_angle_deg, sw::barrier_density_kg_m3,
                                    sw::base_friction,  sw::analytical_tau};
  sw::SceneValues base = valid_base();
  base.analytical_tau_given = true;
  base.value[sw::base_width_m] = 6.0;  // room for the face at 60 degrees
  base.value[sw::empirical_kappa] = 1.0;
  expect_scalar_outputs<TypeParam>(base, targets, points_of(targets, n, 1), n);
  base.fixed = true;  // an infinitely heavy barrier
  expect_scalar_outputs<TypeParam>(base, targets, points_of(targets, n, 2), n);
}

TYPED_TEST(ClosedFormSweepKernel, BlocksOfSingleFieldChecksGiveTheScalarModelsOutputs) {
  // No face dimension sampled: each check is of one field against its own range, which the host
  // makes a block of samples at a time, as it writes the models' inputs (the shipped study's
  // case). Every kind of scene those inputs depend on: front-body-tail (the integer body squares
  // checked) or rectangle, a barrier given by its density, its mass or fixed, the analytical
  // coefficients given or the defaults.
  const std::size_t n = 1037;
  const std::vector<int> targets = {sw::thickness_m, sw::velocity_m_s, sw::body_squares,
                                    sw::barrier_density_kg_m3, sw::base_friction};
  sw::SceneValues base = valid_base();
  expect_scalar_outputs<TypeParam>(base, targets, points_of(targets, n, 3), n);
  base.fixed = true;
  expect_scalar_outputs<TypeParam>(base, targets, points_of(targets, n, 4), n);
  base.fixed = false;
  base.barrier_given_by_mass = true;
  base.analytical_tau_given = base.analytical_lambda_given = true;
  expect_scalar_outputs<TypeParam>(base, targets, points_of(targets, n, 5), n);
  base.rectangle = true;  // the body squares unused: their invalid values pass
  const std::vector<int> with_length = {sw::thickness_m, sw::length_m, sw::base_friction};
  expect_scalar_outputs<TypeParam>(base, with_length, points_of(with_length, n, 6), n);
}

TYPED_TEST(ClosedFormSweepKernel, SampledCoefficientsAndMomentumVariantsRunOneSampleAtATime) {
  const std::size_t n = 301;
  sw::SceneValues base = valid_base();
  // The empirical coefficient a1 sampled: the empirical model a sample at a time, the
  // analytical one batched.
  const std::vector<int> with_a1 = {sw::thickness_m, sw::velocity_m_s, sw::empirical_a1};
  expect_scalar_outputs<TypeParam>(base, with_a1, points_of(with_a1, n, 3), n);
  // Both momentum-consistent variants: both a sample at a time.
  base.empirical_momentum = base.analytical_momentum = true;
  const std::vector<int> plain = {sw::thickness_m, sw::velocity_m_s, sw::base_friction};
  expect_scalar_outputs<TypeParam>(base, plain, points_of(plain, n, 4), n);
}

}  // namespace
