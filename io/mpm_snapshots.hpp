// MPM particle snapshots (MpmOutcome::snapshots) in the HDF5 result file, plus an XDMF file that
// lets ParaView (or VisIt) open them as a time series of point clouds.
//
// HDF5 layout, inside the `mpm` method group (written through write_results' `extra` callback):
//   /mpm/snapshots                  group; attributes count (int64, number of snapshots) and
//                                   materials (the material names, comma-separated, indexed by
//                                   `material`)
//   /mpm/snapshots/NNNNNN           one group per snapshot, NNNNNN = 000000, 000001, ...;
//                                   attributes time (double) and time_units ("s")
//     id                 n      1     int64: the point's index among the run's initial points
//     material           n      1     int64: index into the root's `materials`
//     position           n x 3  m     x, y, 0 (z = 0: XDMF geometry and vectors are 3-D)
//     displacement       n x 3  m     since the first snapshot (t = 0)
//     velocity           n x 3  m/s   vx, vy, 0
//     mass               n      kg/m
//     volume             n      m^2   current
//     volumetric_strain  n      1     V / V0 - 1 (expansion positive)
//     stress             n x 4  Pa    xx, yy, xy, zz (Cauchy, tension positive)
//     deviatoric_strain  n      1     accumulated equivalent shear strain
//     plastic_work       n      J/m   dissipated by plastic flow (accumulated)
//     pore_pressure      n      Pa    saturated runs only
//     barrier_outline    4 x 3  m     impact scenes: the barrier's corners where it stands (upstream
//                                     toe, upstream crest, downstream crest, downstream toe)
//   every dataset has string attributes `units` and `description`; the vectors and stress also
//   `components`.
//
// XDMF: `<stem>.xdmf` next to the HDF5 file, a temporal collection of Uniform Polyvertex grids
// (one per snapshot) that refer to the datasets above by the HDF5 file's name (relative, so the
// two files move together). Stress components are exposed as scalars stress_xx, stress_yy,
// stress_xy, stress_zz through HyperSlab selections of the n x 4 dataset. Impact scenes add a
// second temporal collection, `barrier`: one quadrilateral per snapshot, where the barrier stands.
#pragma once
#include <string>
#include <vector>

#include "model/mpm_runner.hpp"

namespace lsi {

// Writes the snapshots into the open HDF5 file `file_id` (an hid_t): the `mpm` group must exist.
// Throws std::runtime_error on any HDF5 failure.
void write_mpm_snapshots(long long file_id, const std::vector<MpmSnapshot>& snapshots);

// `<dir>/<stem>.xdmf` for `<dir>/<stem>.<ext>`.
std::string mpm_snapshots_xdmf_path(const std::string& h5_path);

// Writes the XDMF description of the snapshots written by write_mpm_snapshots into `h5_path`,
// atomically (temporary file + rename), at mpm_snapshots_xdmf_path(h5_path). Throws
// std::runtime_error (path + what failed); the temporary file is then removed.
void write_mpm_snapshots_xdmf(const std::string& h5_path,
                              const std::vector<MpmSnapshot>& snapshots);

}  // namespace lsi
