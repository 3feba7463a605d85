// The barrier as the solvers hold it: the barrier, the contact forces of the last step, the
// contact impulse accumulated since the caller last took it (per face, and per height band of the
// upstream face when the barrier asks for bands), and the step that moves the barrier under the
// step's contact forces. Shared by the dry and the saturated solver. The bands: the contact adds
// each face node's normal impulse into its node row (barrier_contact.hpp), where it stays, step
// after step, until the caller takes the bands; then each row's impulse is shared among the bands
// its tributary height overlaps (height_bands.hpp), row by row from the lowest: sums in one order
// whatever the threads, so a run's bands are the same from run to run. The barrier slides
// horizontally, so a row keeps its height above the toe, and the sharing, linear in the impulse,
// gives the sum over the steps what it would give each step's. No band work between the steps.
#pragma once
#include <Kokkos_Core.hpp>
#include <algorithm>
#include <vector>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/barrier.hpp"
#include "kernels/mpm/barrier_contact.hpp"
#include "kernels/mpm/height_bands.hpp"

namespace lsi::mpm {

template <class MemorySpace>
class BarrierCoupling {
  using Exec = typename MemorySpace::execution_space;

 public:
  void attach(const Barrier& b) {
    barrier_ = b;
    active_ = true;
    const int n = b.face_bands();
    band_impulse_.assign(static_cast<std::size_t>(n), 0.0);
  }
  // The upstream face's normal impulse per node row of the grid since the bands were last taken
  // (N s/m), added to by the step's barrier_contact calls; empty without bands.
  const Kokkos::View<double*, MemorySpace>& row_impulse() const { return row_impulse_; }
  // Before the step's barrier_contact calls on grid g (its rows: origin, dx, ny).
  template <class GridT>
  void begin_step(const GridT& g) {
    if (band_impulse_.empty()) return;
    if (row_impulse_.extent(0) == static_cast<std::size_t>(g.ny) && row_y0_ == g.origin[1] &&
        row_dx_ == g.dx)
      return;
    if (row_impulse_.extent(0) > 0) share_rows_among_bands();  // rows of another grid
    row_impulse_ = Kokkos::View<double*, MemorySpace>("face_row_impulse", g.ny);
    row_host_ = Kokkos::create_mirror_view(row_impulse_);
    row_y0_ = g.origin[1];
    row_dx_ = g.dx;
  }
  bool active() const { return active_; }
  const Barrier& barrier() const { return barrier_; }
  // Contact forces on the barrier during the last step, per face (N/m).
  const BarrierContactReport& contact() const { return contact_; }

  // Records the step's contact (the sum over the phases) and moves a free barrier under it.
  // Returns the work the contact took from the material (J/m).
  double apply(const BarrierContactReport& contact, double dt) {
    contact_ = contact;
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) impulse_[k][d] += contact_.force[k][d] * dt;
    moment_impulse_ += contact_.upstream_moment * dt;
    if (!barrier_.fixed) barrier_.motion.advance(contact_.total(0), contact_.total(1), dt);
    return contact_.work;
  }

  // Contact impulse on the barrier per face (N s/m, x and y) since the last call; resets it.
  void take_impulse(double impulse[3][2]) {
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) {
        impulse[k][d] = impulse_[k][d];
        impulse_[k][d] = 0.0;
      }
  }
  // The time integral of the upstream face's overturning moment (N m s/m) since the last call;
  // resets it.
  double take_moment_impulse() {
    const double m = moment_impulse_;
    moment_impulse_ = 0.0;
    return m;
  }
  // The upstream face's normal impulse per height band (N s/m, the lowest band first) since the
  // last call; resets it. Empty without bands.
  std::vector<double> take_band_impulse() {
    if (row_impulse_.extent(0) > 0) share_rows_among_bands();
    std::vector<double> taken(band_impulse_.size(), 0.0);
    taken.swap(band_impulse_);
    return taken;
  }

 private:
  bool active_ = false;
  Barrier barrier_;
  BarrierContactReport contact_;
  double impulse_[3][2] = {{0, 0}, {0, 0}, {0, 0}};
  double moment_impulse_ = 0.0;
  // The rows' impulse into the bands' impulse; the rows left at zero.
  void share_rows_among_bands() {
    copy_and_wait<Exec>(row_host_, row_impulse_);
    const int bands = static_cast<int>(band_impulse_.size());
    const double toe = barrier_.shape.toe[1];
    for (std::size_t j = 0; j < row_host_.extent(0); ++j) {
      const double impulse = row_host_(j);
      if (impulse == 0.0) continue;
      const double y = row_y0_ + static_cast<double>(j) * row_dx_;
      share_among_bands(bands, barrier_.face_band_height, y - toe, row_dx_, impulse,
                        [&](int k, double share) { band_impulse_[k] += share; });
    }
    fill<Exec>(row_impulse_, 0.0);
  }

  Kokkos::View<double*, MemorySpace> row_impulse_;
  typename Kokkos::View<double*, MemorySpace>::HostMirror row_host_;
  double row_y0_ = 0.0, row_dx_ = 0.0;
  std::vector<double> band_impulse_;
};

}  // namespace lsi::mpm
