// The instance kernels launch on (kernels/common/execution_instance.hpp) and a host thread's own
// stream (kernels/common/own_stream.hpp), once per backend: on a host space the policies are the
// plain ones (a host run is what it was without them); on a device a thread with a stream of its
// own launches there and gets the default instance back after; fill and copy_and_wait move the
// values they say, in order with the kernels around them, with and without a stream of its own.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <type_traits>

#include "kernels/common/execution_instance.hpp"
#include "kernels/common/own_stream.hpp"
#include "support/backends.hpp"

namespace {

template <class Exec>
class ExecutionInstance : public ::testing::Test {};
TYPED_TEST_SUITE(ExecutionInstance, lsi::test::Backends);

TYPED_TEST(ExecutionInstance, HostSpacesGetThePlainPolicies) {
  using Exec = TypeParam;
  using Range = decltype(lsi::range_policy<Exec>(0, 1));
  using Team = decltype(lsi::team_policy<Exec>(1, 1));
  if constexpr (lsi::runs_on_host<Exec>) {
    EXPECT_TRUE((std::is_same_v<Range, Kokkos::RangePolicy<Exec>>));
    EXPECT_TRUE((std::is_same_v<Team, Kokkos::TeamPolicy<Exec>>));
  } else {
    EXPECT_FALSE((std::is_same_v<Range, Kokkos::RangePolicy<Exec>>)) << "the light-weight hint";
  }
  const auto policy = lsi::range_policy<Exec>(3, 11);
  EXPECT_EQ(policy.begin(), 3);
  EXPECT_EQ(policy.end(), 11);
}

#if defined(KOKKOS_ENABLE_CUDA)
TYPED_TEST(ExecutionInstance, AThreadWithAStreamOfItsOwnLaunchesOnIt) {
  using Exec = TypeParam;
  if constexpr (std::is_same_v<Exec, Kokkos::Cuda>) {
    const cudaStream_t shared = Kokkos::Cuda().cuda_stream();
    {
      const lsi::OwnStream<Exec> own;
      EXPECT_NE(lsi::range_policy<Exec>(0, 1).space().cuda_stream(), shared);
      EXPECT_NE(lsi::execution_instance<Exec>().cuda_stream(), shared);
    }
    EXPECT_EQ(lsi::range_policy<Exec>(0, 1).space().cuda_stream(), shared);
  }
}
#endif

// Sum of v(0..n-1) by a reduction on the thread's instance.
template <class Exec, class View>
double sum_of(const View& v) {
  double s = 0.0;
  Kokkos::parallel_reduce(
      "sum_of", lsi::range_policy<Exec>(0, static_cast<int>(v.extent(0))),
      KOKKOS_LAMBDA(const int i, double& acc) { acc += v(i); }, s);
  return s;
}

template <class Exec>
void fill_and_copy_in_order() {
  using Mem = typename Exec::memory_space;
  const int n = 1000;
  Kokkos::View<double*, Mem> v("v", n);
  // A kernel, then a fill that must come after it, then a copy that must see the fill.
  Kokkos::parallel_for(
      "set", lsi::range_policy<Exec>(0, n), KOKKOS_LAMBDA(const int i) { v(i) = i; });
  lsi::fill<Exec>(v, 2.5);
  auto host = Kokkos::create_mirror_view(Kokkos::HostSpace(), v, Kokkos::WithoutInitializing);
  lsi::copy_and_wait<Exec>(host, v);
  for (int i = 0; i < n; i += 99) ASSERT_EQ(host(i), 2.5) << i;
  // Back to the device: the next kernel sees the host's values.
  for (int i = 0; i < n; ++i) host(i) = i;
  lsi::copy_and_wait<Exec>(v, host);
  EXPECT_EQ(sum_of<Exec>(v), 0.5 * n * (n - 1));  // integers: exact in any order
}

TYPED_TEST(ExecutionInstance, FillAndCopyAndWaitMoveTheValuesInOrder) {
  fill_and_copy_in_order<TypeParam>();
  const lsi::OwnStream<TypeParam> own;  // nothing on a host space
  fill_and_copy_in_order<TypeParam>();
}

}  // namespace
