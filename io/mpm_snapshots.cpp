// MPM particle snapshots: HDF5 groups and the XDMF index; layout in mpm_snapshots.hpp.
#include "io/mpm_snapshots.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "io/text_file.hpp"

namespace lsi {
namespace {

namespace fs = std::filesystem;

// Owns one hid_t; throws (with `what`) when the id is invalid.
class Id {
 public:
  Id(hid_t id, herr_t (*closer)(hid_t), const std::string& what) : id_(id), closer_(closer) {
    if (id_ < 0) throw std::runtime_error("mpm snapshots: " + what);
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() { closer_(id_); }
  operator hid_t() const { return id_; }  // NOLINT: passes straight into the C API

 private:
  hid_t id_;
  herr_t (*closer_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("mpm snapshots: " + what);
}

void string_attribute(hid_t obj, const char* name, const std::string& value) {
  Id type(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create the string type");
  check(H5Tset_size(type, H5T_VARIABLE), "cannot make the string type variable-length");
  check(H5Tset_cset(type, H5T_CSET_UTF8), "cannot set the string type to UTF-8");
  Id space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  Id attr(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
          std::string("cannot create attribute '") + name + "'");
  const char* ptr = value.c_str();
  check(H5Awrite(attr, type, &ptr), std::string("cannot write attribute '") + name + "'");
}

void double_attribute(hid_t obj, const char* name, double value) {
  Id space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  Id attr(H5Acreate2(obj, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
          std::string("cannot create attribute '") + name + "'");
  check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value),
        std::string("cannot write attribute '") + name + "'");
}

void int_attribute(hid_t obj, const char* name, long long value) {
  Id space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  Id attr(H5Acreate2(obj, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
          std::string("cannot create attribute '") + name + "'");
  check(H5Awrite(attr, H5T_NATIVE_LLONG, &value),
        std::string("cannot write attribute '") + name + "'");
}

// An n (cols == 0) or n x cols double dataset from row-major `data`, with `units` and
// `description` attributes and, if given, a `components` attribute.
void dataset(hid_t group, const char* name, const std::vector<double>& data, size_t n, size_t cols,
             const char* units, const char* description, const char* components = nullptr) {
  const hsize_t dims[2] = {static_cast<hsize_t>(n), static_cast<hsize_t>(cols)};
  Id space(H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr), H5Sclose,
           std::string("cannot create the dataspace of '") + name + "'");
  Id dset(H5Dcreate2(group, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          H5Dclose, std::string("cannot create dataset '") + name + "'");
  if (n > 0)
    check(H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          std::string("cannot write dataset '") + name + "'");
  string_attribute(dset, "units", units);
  string_attribute(dset, "description", description);
  if (components != nullptr) string_attribute(dset, "components", components);
}

// An n integer dataset (int64 on disk) with `units` and `description` attributes.
template <class Int>
void int_dataset(hid_t group, const char* name, const std::vector<Int>& data, const char* units,
                 const char* description) {
  const hsize_t dims[1] = {static_cast<hsize_t>(data.size())};
  Id space(H5Screate_simple(1, dims, nullptr), H5Sclose,
           std::string("cannot create the dataspace of '") + name + "'");
  Id dset(H5Dcreate2(group, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          H5Dclose, std::string("cannot create dataset '") + name + "'");
  const std::vector<long long> wide(data.begin(), data.end());
  if (!wide.empty())
    check(H5Dwrite(dset, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, wide.data()),
          std::string("cannot write dataset '") + name + "'");
  string_attribute(dset, "units", units);
  string_attribute(dset, "description", description);
}

// n x 2 -> n x 3 with z = 0.
std::vector<double> with_zero_z(const std::vector<double>& xy, size_t n) {
  std::vector<double> xyz(3 * n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    xyz[3 * i] = xy[2 * i];
    xyz[3 * i + 1] = xy[2 * i + 1];
  }
  return xyz;
}

std::string group_name(size_t k) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%06zu", k);
  return buf;
}

// Text that reads back as the same double.
std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

}  // namespace

void write_mpm_snapshots(long long file_id, const std::vector<MpmSnapshot>& snapshots) {
  const hid_t file = static_cast<hid_t>(file_id);
  Id mpm(H5Gopen2(file, "mpm", H5P_DEFAULT), H5Gclose, "cannot open group 'mpm'");
  Id root(H5Gcreate2(mpm, "snapshots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
          "cannot create group 'mpm/snapshots'");
  int_attribute(root, "count", static_cast<long long>(snapshots.size()));
  if (!snapshots.empty()) {
    std::string names;
    for (size_t m = 0; m < snapshots.front().material_names.size(); ++m)
      names += (m ? "," : "") + snapshots.front().material_names[m];
    // `material` of a point indexes this comma-separated list.
    string_attribute(root, "materials", names);
  }
  for (size_t k = 0; k < snapshots.size(); ++k) {
    const MpmSnapshot& s = snapshots[k];
    const size_t n = static_cast<size_t>(s.count);
    if (s.position.size() != 2 * n || s.velocity.size() != 2 * n || s.stress.size() != 4 * n ||
        s.deviatoric_strain.size() != n || s.plastic_work.size() != n || s.id.size() != n ||
        s.material.size() != n || s.mass.size() != n || s.volume.size() != n ||
        s.volumetric_strain.size() != n || s.displacement.size() != 2 * n ||
        (!s.barrier_outline.empty() && s.barrier_outline.size() != 8) ||
        (!s.face_pressure.empty() && s.face_band_points.size() != 2 * (s.face_pressure.size() + 1)))
      throw std::runtime_error("mpm snapshots: snapshot " + std::to_string(k) +
                               ": array sizes do not match its particle count");
    const std::string name = group_name(k);
    Id g(H5Gcreate2(root, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
         "cannot create group 'mpm/snapshots/" + name + "'");
    double_attribute(g, "time", s.time);
    string_attribute(g, "time_units", "s");
    dataset(g, "position", with_zero_z(s.position, n), n, 3, "m", "position of each point",
            "x y z(=0)");
    dataset(g, "velocity", with_zero_z(s.velocity, n), n, 3, "m/s", "velocity of each point",
            "x y z(=0)");
    dataset(g, "stress", s.stress, n, 4, "Pa", "Cauchy stress of each point, tension positive",
            "xx yy xy zz");
    dataset(g, "deviatoric_strain", s.deviatoric_strain, n, 0, "1",
            "accumulated equivalent shear strain of each point");
    dataset(g, "plastic_work", s.plastic_work, n, 0, "J/m",
            "work dissipated by plastic flow in each point, accumulated");
    if (s.pore_pressure.size() == n)
      dataset(g, "pore_pressure", s.pore_pressure, n, 0, "Pa",
              "pore pressure of each point, compression positive");
    int_dataset(g, "id", s.id, "1", "index of each point among the run's initial points");
    int_dataset(g, "material", s.material, "1",
                "material of each point: index into /mpm/snapshots' materials");
    dataset(g, "displacement", with_zero_z(s.displacement, n), n, 3, "m",
            "displacement of each point since the first snapshot", "x y z(=0)");
    dataset(g, "mass", s.mass, n, 0, "kg/m", "mass of each point per metre of width");
    dataset(g, "volume", s.volume, n, 0, "m^2", "current volume of each point per metre of width");
    dataset(g, "volumetric_strain", s.volumetric_strain, n, 0, "1",
            "V / V0 - 1 of each point (expansion positive)");
    if (!s.barrier_outline.empty())
      dataset(g, "barrier_outline", with_zero_z(s.barrier_outline, 4), 4, 3, "m",
              "the barrier's corners where it stands: upstream toe, upstream crest, downstream "
              "crest, downstream toe",
              "x y z(=0)");
    if (!s.face_pressure.empty()) {
      const size_t bands = s.face_pressure.size();
      dataset(g, "face_pressure", s.face_pressure, bands, 0, "Pa",
              "mean normal stress on each height band of the upstream face over the output "
              "interval that ends at the snapshot, from the base up");
      dataset(g, "face_band_points", with_zero_z(s.face_band_points, bands + 1), bands + 1, 3, "m",
              "the bands' ends along the upstream face where the barrier stands, from the toe up",
              "x y z(=0)");
    }
  }
}

std::string mpm_snapshots_xdmf_path(const std::string& h5_path) {
  fs::path p(h5_path);
  p.replace_extension(".xdmf");
  return p.string();
}

void write_mpm_snapshots_xdmf(const std::string& h5_path,
                              const std::vector<MpmSnapshot>& snapshots) {
  const std::string path = mpm_snapshots_xdmf_path(h5_path);
  const std::string h5 = xml_escape(fs::path(h5_path).filename().string());
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n"
    << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"2.0\">\n"
    << "  <Domain>\n"
    << "    <Grid Name=\"mpm_particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (size_t k = 0; k < snapshots.size(); ++k) {
    const MpmSnapshot& s = snapshots[k];
    const std::string n = std::to_string(s.count);
    const std::string at = h5 + ":/mpm/snapshots/" + group_name(k) + "/";
    const auto item = [&](const std::string& dims, const std::string& dataset) {
      return "<DataItem Dimensions=\"" + dims +
             "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + at + dataset +
             "</DataItem>";
    };
    const auto int_item = [&](const std::string& dims, const std::string& dataset) {
      return "<DataItem Dimensions=\"" + dims +
             "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" + at + dataset + "</DataItem>";
    };
    x << "      <Grid Name=\"particles_" << group_name(k) << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << exact(s.time) << "\"/>\n"
      << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
      << "\" NodesPerElement=\"1\"/>\n"
      << "        <Geometry GeometryType=\"XYZ\">\n"
      << "          " << item(n + " 3", "position") << "\n"
      << "        </Geometry>\n"
      << "        <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n"
      << "          " << item(n + " 3", "velocity") << "\n"
      << "        </Attribute>\n"
      << "        <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n"
      << "          " << item(n + " 3", "displacement") << "\n"
      << "        </Attribute>\n";
    for (const char* integer : {"id", "material"})
      x << "        <Attribute Name=\"" << integer
        << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        << "          " << int_item(n, integer) << "\n"
        << "        </Attribute>\n";
    const char* components[] = {"xx", "yy", "xy", "zz"};
    for (int c = 0; c < 4; ++c) {
      x << "        <Attribute Name=\"stress_" << components[c]
        << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        << "          <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << n << " 1\">\n"
        << "            <DataItem Dimensions=\"3 2\" Format=\"XML\">0 " << c << " 1 1 " << n
        << " 1</DataItem>\n"
        << "            " << item(n + " 4", "stress") << "\n"
        << "          </DataItem>\n"
        << "        </Attribute>\n";
    }
    std::vector<const char*> scalars = {"mass", "volume", "volumetric_strain", "deviatoric_strain",
                                        "plastic_work"};
    if (!snapshots[k].pore_pressure.empty()) scalars.push_back("pore_pressure");
    for (const char* scalar : scalars)
      x << "        <Attribute Name=\"" << scalar
        << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        << "          " << item(n, scalar) << "\n"
        << "        </Attribute>\n";
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n";
  // The barrier, where it stands at each snapshot: one quadrilateral.
  if (!snapshots.empty() && !snapshots.front().barrier_outline.empty()) {
    x << "    <Grid Name=\"barrier\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t k = 0; k < snapshots.size(); ++k)
      x << "      <Grid Name=\"barrier_" << group_name(k) << "\" GridType=\"Uniform\">\n"
        << "        <Time Value=\"" << exact(snapshots[k].time) << "\"/>\n"
        << "        <Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"1\">\n"
        << "          <DataItem Dimensions=\"1 4\" NumberType=\"Int\" Format=\"XML\">0 1 2 3"
        << "</DataItem>\n"
        << "        </Topology>\n"
        << "        <Geometry GeometryType=\"XYZ\">\n"
        << "          <DataItem Dimensions=\"4 3\" NumberType=\"Float\" Precision=\"8\" "
        << "Format=\"HDF\">" << h5 << ":/mpm/snapshots/" << group_name(k)
        << "/barrier_outline</DataItem>\n"
        << "        </Geometry>\n"
        << "      </Grid>\n";
    x << "    </Grid>\n";
  }
  // The upstream face's bands: one line segment each, with its normal stress.
  if (!snapshots.empty() && !snapshots.front().face_pressure.empty()) {
    x << "    <Grid Name=\"barrier_face\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t k = 0; k < snapshots.size(); ++k) {
      const size_t bands = snapshots[k].face_pressure.size();
      const std::string at = h5 + ":/mpm/snapshots/" + group_name(k) + "/";
      x << "      <Grid Name=\"barrier_face_" << group_name(k) << "\" GridType=\"Uniform\">\n"
        << "        <Time Value=\"" << exact(snapshots[k].time) << "\"/>\n"
        << "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << bands
        << "\" NodesPerElement=\"2\">\n"
        << "          <DataItem Dimensions=\"" << bands
        << " 2\" NumberType=\"Int\" Format=\"XML\">";
      for (size_t b = 0; b < bands; ++b) x << (b ? " " : "") << b << " " << b + 1;
      x << "</DataItem>\n"
        << "        </Topology>\n"
        << "        <Geometry GeometryType=\"XYZ\">\n"
        << "          <DataItem Dimensions=\"" << bands + 1
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << at
        << "face_band_points</DataItem>\n"
        << "        </Geometry>\n"
        << "        <Attribute Name=\"face_pressure\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
        << "          <DataItem Dimensions=\"" << bands
        << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << at
        << "face_pressure</DataItem>\n"
        << "        </Attribute>\n"
        << "      </Grid>\n";
    }
    x << "    </Grid>\n";
  }
  x << "  </Domain>\n"
    << "</Xdmf>\n";

  write_text_atomically(path, x.str());
}

}  // namespace lsi
