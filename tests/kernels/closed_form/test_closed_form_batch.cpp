// The batched closed-form kernels (kernels/closed_form/batch.hpp) give the scalar models' answers
// on every Kokkos backend compiled in: the same tests, once per execution space.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>

#include "kernels/closed_form/batch.hpp"

namespace {
using namespace lsi;

template <class ExecSpace>
class ClosedFormBatch : public ::testing::Test {};

using Spaces = ::testing::Types<
#ifdef KOKKOS_ENABLE_SERIAL
    Kokkos::Serial
#endif
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
    ,
#endif
#ifdef KOKKOS_ENABLE_OPENMP
    Kokkos::OpenMP
#endif
#ifdef KOKKOS_ENABLE_CUDA
    ,
    Kokkos::Cuda
#endif
    >;
TYPED_TEST_SUITE(ClosedFormBatch, Spaces);

TYPED_TEST(ClosedFormBatch, MatchesScalarModels) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  const int n = 2003;  // not a multiple of the host block: the last, partial block runs too
  Kokkos::View<double* [10], Kokkos::LayoutLeft, Kokkos::HostSpace> host("inputs", n);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double h = 0.5 + 3 * u(rng), v = 2 + 15 * u(rng), rho = 1600 + 600 * u(rng);
    const double L = (2 + int(8 * u(rng))) * h;
    host(i, 0) = h;
    host(i, 1) = v;
    host(i, 2) = rho;
    host(i, 3) = rho * L * h;
    host(i, 4) = L;
    host(i, 5) = (i % 10 == 0) ? std::numeric_limits<double>::infinity() : 5e3 + 1e5 * u(rng);
    host(i, 6) = (i % 13 == 0) ? 0.0 : 0.6 * u(rng);  // no base friction: never stops
    host(i, 7) = (i % 7 == 0 ? 90.0 : 20 + 70 * u(rng)) * 3.14159265358979323846 / 180;
    host(i, 8) = 0.05 + 0.9 * u(rng);
    host(i, 9) = 0.1 + 0.9 * u(rng);
  }
  auto dev = Kokkos::create_mirror_view_and_copy(Mem(), host);
  ClosedFormInputs<Mem> in;
  in.thickness = Kokkos::subview(dev, Kokkos::ALL, 0);
  in.velocity = Kokkos::subview(dev, Kokkos::ALL, 1);
  in.density = Kokkos::subview(dev, Kokkos::ALL, 2);
  in.landslide_mass = Kokkos::subview(dev, Kokkos::ALL, 3);
  in.equivalent_length = Kokkos::subview(dev, Kokkos::ALL, 4);
  in.barrier_mass = Kokkos::subview(dev, Kokkos::ALL, 5);
  in.base_friction = Kokkos::subview(dev, Kokkos::ALL, 6);
  in.face_angle = Kokkos::subview(dev, Kokkos::ALL, 7);
  in.tau = Kokkos::subview(dev, Kokkos::ALL, 8);
  in.lambda = Kokkos::subview(dev, Kokkos::ALL, 9);
  for (int model = 0; model < 2; ++model) {
    ClosedFormOutputs<Mem> out{
        Kokkos::View<double*, Mem>("peak", n), Kokkos::View<double*, Mem>("T1", n),
        Kokkos::View<double*, Mem>("T2", n), Kokkos::View<double*, Mem>("dx", n)};
    if (model == 0)
      evaluate_two_body_batch(Exec(), in, out);
    else
      evaluate_empirical_batch(Exec(), in, EmpiricalCoefficients{}, out);
    Exec().fence();
    auto peak = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out.peak_force);
    auto T2 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out.impact_duration);
    auto dx = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out.final_displacement);
    // Samples in each of the barrier's outcomes (barrier_motion's phases): fixed, stuck, stopped
    // by friction before T2, stopped after T2, never stopped.
    int fixed = 0, stuck = 0, before_T2 = 0, after_T2 = 0, never = 0;
    for (int i = 0; i < n; ++i) {
      ForcePulse p;
      if (model == 0) {
        p = two_body_impact(host(i, 3), host(i, 1), host(i, 4), host(i, 5),
                            TwoBodyCoefficients{host(i, 9), host(i, 8)})
                .pulse;
      } else {
        EmpiricalCoefficients c;
        c.tau = host(i, 8);
        p = empirical_impact(host(i, 0), host(i, 1), host(i, 2), host(i, 3), host(i, 7), c).pulse;
      }
      double expected = 0.0;
      if (std::isfinite(host(i, 5))) {
        const SlidingBlock b{host(i, 5), host(i, 6),
                             resolve_face_force(host(i, 7)).sliding_drive(host(i, 6))};
        const BarrierMotion m = barrier_motion(p, b);
        expected = m.final_displacement;
        stuck += !m.moves;
        before_T2 += m.moves && m.stop_time <= p.duration;
        after_T2 += m.moves && m.stop_time > p.duration && std::isfinite(m.stop_time);
        never += m.moves && std::isinf(m.stop_time);
      } else {
        ++fixed;
      }
      // Same code on another backend: identical up to floating-point contraction (1e-12).
      EXPECT_NEAR(peak(i), p.peak, 1e-12 * p.peak) << i;
      EXPECT_NEAR(T2(i), p.duration, 1e-12 * p.duration) << i;
      if (std::isinf(expected))
        EXPECT_TRUE(std::isinf(dx(i))) << i;
      else
        EXPECT_NEAR(dx(i), expected, 1e-10 * (1 + expected)) << i;
    }
    // The sample exercises every outcome (the batch selects among them without branches).
    std::printf("[ model %d ] fixed %d, stuck %d, stops before T2 %d, after T2 %d, never %d\n",
                model, fixed, stuck, before_T2, after_T2, never);
    EXPECT_GT(fixed, 0);
    EXPECT_GT(stuck, 0);
    EXPECT_GT(before_T2, 0);
    EXPECT_GT(after_T2, n / 10);
    EXPECT_GT(never, 0);
  }
}
}  // namespace

int main(int argc, char** argv) {
  setenv("OMP_PROC_BIND", "false", /*overwrite=*/0);  // no Kokkos warning in test discovery
  ::testing::InitGoogleTest(&argc, argv);
  Kokkos::ScopeGuard kokkos(argc, argv);
  return RUN_ALL_TESTS();
}
