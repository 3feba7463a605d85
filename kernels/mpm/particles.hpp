// Material points as flat structure-of-arrays Views (no object per particle). 2D plane strain:
// the stress keeps sigma_zz. Units SI, per metre of out-of-plane width.
// Every multi-component field is laid out component by component (PointLayout, LayoutLeft: the
// x of all points, then the y of all points), on the host as on a device, so that consecutive
// points are consecutive in memory for each component: what a loop vectorised over points (and
// a GPU's coalesced access) needs. Code that copies a field must use element access, p(q, k), or
// views of the same layout (create_mirror_view), never the raw memory of an interleaved array.
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::mpm {

enum StressComponent { XX = 0, YY = 1, XY = 2, ZZ = 3 };

using PointLayout = Kokkos::LayoutLeft;

// Numbers the points 0, 1, ... in their order of creation (Particles::id).
template <class MemorySpace>
void number_points(const Kokkos::View<int*, MemorySpace>& id) {
  auto host = Kokkos::create_mirror_view(id);
  for (int q = 0; q < static_cast<int>(host.extent(0)); ++q) host(q) = q;
  Kokkos::deep_copy(id, host);
}

// A field added here must also be moved by the sort (PointSorter::apply, sort_points.hpp).
template <class MemorySpace>
struct Particles {
  int count = 0;
  Kokkos::View<double* [2], PointLayout, MemorySpace> position;   // m
  Kokkos::View<double* [2], PointLayout, MemorySpace> velocity;   // m/s
  Kokkos::View<double* [2][2], PointLayout, MemorySpace> affine;  // APIC C = B D^-1, 1/s
  // L = grad v, 1/s: of the last step where a pass after the G2P reads it (the separate
  // stress update); the fused G2P and stress update keep it in registers and leave this as it was.
  Kokkos::View<double* [2][2], PointLayout, MemorySpace> velocity_gradient;
  Kokkos::View<double* [4], PointLayout, MemorySpace> stress;  // Cauchy, Pa (tension positive)
  Kokkos::View<double*, MemorySpace> mass;                     // kg/m
  Kokkos::View<double*, MemorySpace> volume;                   // m^2 (current)
  Kokkos::View<double*, MemorySpace> volume0;                  // m^2 (initial)
  Kokkos::View<double*, MemorySpace> plastic_work;             // J/m dissipated (accumulated)
  Kokkos::View<double*, MemorySpace> deviatoric_strain;  // accumulated equivalent shear strain
  Kokkos::View<int*, MemorySpace> material;              // index into the material table
  // The point's index among the points as they were created: the solvers reorder the points
  // (sort_points.hpp), the id names the same point throughout a run.
  Kokkos::View<int*, MemorySpace> id;

  Particles() = default;
  explicit Particles(int n) : count(n) {
    position = decltype(position)("p_position", n);
    velocity = decltype(velocity)("p_velocity", n);
    affine = decltype(affine)("p_affine", n);
    velocity_gradient = decltype(velocity_gradient)("p_velocity_gradient", n);
    stress = decltype(stress)("p_stress", n);
    mass = decltype(mass)("p_mass", n);
    volume = decltype(volume)("p_volume", n);
    volume0 = decltype(volume0)("p_volume0", n);
    plastic_work = decltype(plastic_work)("p_plastic_work", n);
    deviatoric_strain = decltype(deviatoric_strain)("p_deviatoric_strain", n);
    material = decltype(material)("p_material", n);
    id = decltype(id)("p_id", n);
    number_points(id);
  }
};

// The fields of host Particles as raw component arrays, with the same element access
// (p.position(q, r), p.mass(q), ...), for loops over points that the compiler is to vectorise:
// built inside a kernel, before its loop, the pointers are values the loop's stores cannot
// change, and the loop needs no View bookkeeping.
template <class T>
struct PointColumn {
  T* c;
  KOKKOS_FORCEINLINE_FUNCTION T& operator()(const int q) const { return c[q]; }
};
template <int N>
struct PointColumns {
  double* c[N];
  KOKKOS_FORCEINLINE_FUNCTION double& operator()(const int q, const int k) const { return c[k][q]; }
};
struct PointMatrices {
  double* c[2][2];
  KOKKOS_FORCEINLINE_FUNCTION double& operator()(const int q, const int r, const int k) const {
    return c[r][k][q];
  }
};
struct PointArrays {
  PointColumns<2> position, velocity;
  PointMatrices affine, velocity_gradient;
  PointColumns<4> stress;
  PointColumn<double> mass, volume, volume0, plastic_work, deviatoric_strain;
  PointColumn<int> material;

  template <class MemorySpace>
  KOKKOS_FORCEINLINE_FUNCTION explicit PointArrays(const Particles<MemorySpace>& p)
      : mass{p.mass.data()},
        volume{p.volume.data()},
        volume0{p.volume0.data()},
        plastic_work{p.plastic_work.data()},
        deviatoric_strain{p.deviatoric_strain.data()},
        material{p.material.data()} {
    // Written out, not in loops: each pointer must become a value of its own (a loop here
    // kept them in memory, where the vectoriser does not look through them).
    position = {{&p.position(0, 0), &p.position(0, 1)}};
    velocity = {{&p.velocity(0, 0), &p.velocity(0, 1)}};
    affine = {{{&p.affine(0, 0, 0), &p.affine(0, 0, 1)}, {&p.affine(0, 1, 0), &p.affine(0, 1, 1)}}};
    velocity_gradient = {{{&p.velocity_gradient(0, 0, 0), &p.velocity_gradient(0, 0, 1)},
                          {&p.velocity_gradient(0, 1, 0), &p.velocity_gradient(0, 1, 1)}}};
    stress = {{&p.stress(0, 0), &p.stress(0, 1), &p.stress(0, 2), &p.stress(0, 3)}};
  }
};

}  // namespace lsi::mpm
