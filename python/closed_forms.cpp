#include "python/closed_forms.hpp"

#include <pybind11/numpy.h>

#include <Kokkos_Core.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "io/scene_parser.hpp"
#include "io/study_parser.hpp"
#include "io/study_points.hpp"
#include "model/input_error.hpp"
#include "model/messages.hpp"
#include "python/kokkos_work.hpp"
#include "python/method_names.hpp"
#include "python/scene_document.hpp"
#include "sweeps/closed_form_sweep.hpp"

namespace py = pybind11;
using nlohmann::json;

namespace lsi::python {
namespace {

namespace sw = lsi::sweeps;
using Exec = Kokkos::DefaultExecutionSpace;
using Mem = Exec::memory_space;
using Matrix = Kokkos::View<double**, Kokkos::LayoutLeft, Mem>;
constexpr int kOutputs = sw::closed_form_output_count;

// The keys only the MPM reads: given to the closed forms they would change nothing.
bool mpm_only(int field) {
  switch (field) {
    case sw::friction_angle_deg:
    case sw::cohesion_kpa:
    case sw::young_modulus_mpa:
    case sw::poisson_ratio:
    case sw::hydraulic_conductivity_m_s:
    case sw::liquid_bulk_modulus_mpa:
    case sw::liquid_viscosity_kpa_s:
      return true;
    default:
      return false;
  }
}

std::string input_names() {
  std::string out;
  for (int f = 0; f < sw::scene_field_count; ++f)
    if (!mpm_only(f)) out += (out.empty() ? "" : ", ") + std::string(sw::scene_field_name[f]);
  return out;
}

std::string type_name(py::handle value) { return py::str(value.get_type().attr("__name__")); }

// One keyword argument: a scene field and its values (one, or one per point).
struct Input {
  int field = -1;
  std::string name;
  std::vector<double> values;
};

Input input_of(const std::string& name, py::handle value) {
  Input in;
  in.name = name;
  for (int f = 0; f < sw::scene_field_count && in.field < 0; ++f)
    if (name == sw::scene_field_name[f]) in.field = f;
  if (in.field < 0)
    throw py::type_error(
        name + ": not a scene field of the closed forms (allowed: " + input_names() + ")");
  if (mpm_only(in.field))
    throw py::value_error(name + ": read by the MPM only, not by the closed forms (set it in " +
                          "the scene and call run())");
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (value.is_none() || !array)
    throw py::type_error(name + ": a " + type_name(value) +
                         ": give a number or a 1-D array of numbers");
  if (array.ndim() > 1)
    throw py::value_error(name + ": a " + std::to_string(array.ndim()) +
                          "-D array: give a number or a 1-D array of numbers");
  in.values.assign(array.data(), array.data() + array.size());
  return in;
}

// Each value in its field's range (the scene parser's, sweeps/sampled_scene.hpp); the top width's
// bound by the base width, and the face's run-out, are checked with the scene.
void check_ranges(const Input& in) {
  const sw::FieldRange range = sw::scene_field_range(in.field);
  for (std::size_t i = 0; i < in.values.size(); ++i) {
    const double v = in.values[i];
    const bool top_width = in.field == sw::top_width_m;
    if (top_width ? (std::isfinite(v) && v >= 0.0) : sw::in_range(v, range)) continue;
    std::string requirement =
        top_width ? "must be in [0, base_width_m]" : scene_field_requirement(in.field);
    if (!std::isfinite(v)) requirement = "must be finite and " + requirement.substr(8);
    throw py::value_error(in.name + (in.values.size() > 1 ? "[" + std::to_string(i) + "]" : "") +
                          " = " + format_number(v) + ": " + requirement);
  }
}

// Sets a key of the scene document; a parent that is not an object is left for the scene parser
// to refuse with its message.
void set_key(json& doc, const char* pointer, const json& value) {
  try {
    doc[json::json_pointer(pointer)] = value;
  } catch (const json::exception&) {
  }
}

// A whole number as a JSON integer: the parser's messages then show it as a scene file would
// have it (`5`, not `5.0`).
json value_of(double v) {
  return v == std::floor(v) && std::fabs(v) < 0x1p53 ? json(static_cast<long long>(v)) : json(v);
}

// The scene of point i: each input's value at i (or its one value; an empty array sets nothing).
json point_document(json doc, const std::vector<Input>& inputs, std::size_t i) {
  for (const Input& in : inputs)
    if (!in.values.empty())
      set_key(doc, sw::scene_field_pointer[in.field],
              value_of(in.values[in.values.size() > 1 ? i : 0]));
  return doc;
}

std::string at_index(std::size_t n, std::size_t i) {
  return n > 1 ? "index " + std::to_string(i) + ": " : "";
}

struct KernelOutput {
  std::vector<double> values;  // n x 2 * kOutputs, column-major (empirical, then analytical)
  std::vector<int> invalid_field;
};

KernelOutput evaluate(const sw::SceneValues& base, const std::vector<Input>& inputs, std::size_t n,
                      bool empirical, bool analytical) {
  // The inputs that vary take a column of given points (the sweep's Points design); a point
  // without any reads one column that sets nothing.
  std::vector<const Input*> varying;
  for (const Input& in : inputs)
    if (n > 1 && in.values.size() == n) varying.push_back(&in);
  const int dims = varying.empty() ? 1 : static_cast<int>(varying.size());
  std::vector<double> points(n * dims, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d < varying.size(); ++d) points[i * dims + d] = varying[d]->values[i];
  return with_kokkos([&] {
    sw::ClosedFormSweep<Mem> sweep(sw::Sampler<Mem>(points, dims, n));
    sweep.base = base;
    for (int d = 0; d < dims; ++d)
      sweep.target[d] = varying.empty() ? -1 : varying[static_cast<std::size_t>(d)]->field;
    sweep.empirical = empirical;
    sweep.analytical = analytical;
    const Matrix in("lsi::python inputs", n, dims);
    const Matrix out("lsi::python outputs", n, 2 * kOutputs);
    const Kokkos::View<int*, Mem> bad("lsi::python invalid field", n);
    sw::evaluate_closed_form_chunk(Exec(), sweep, 0, in, out, bad);
    Exec().fence();
    KernelOutput r;
    r.values.resize(n * 2 * kOutputs);
    r.invalid_field.resize(n);
    Kokkos::deep_copy(Kokkos::View<double**, Kokkos::LayoutLeft, Kokkos::HostSpace>(
                          r.values.data(), n, 2 * kOutputs),
                      out);
    Kokkos::deep_copy(Kokkos::View<int*, Kokkos::HostSpace>(r.invalid_field.data(), n), bad);
    return r;
  });
}

py::dict closed_forms(py::handle scene, py::handle methods, py::handle fixed,
                      const py::kwargs& fields) {
  const std::vector<std::string> only = method_names(methods, {"empirical", "analytical"});
  std::vector<Input> inputs;
  for (const auto& [key, value] : fields)
    inputs.push_back(input_of(key.cast<std::string>(), value));
  // NumPy's broadcasting of 1-D arrays: every length is n or 1.
  std::size_t n = 1;
  const Input* longest = nullptr;
  for (const Input& in : inputs) {
    const std::size_t length = in.values.size();
    if (length == 1) continue;
    if (!longest) {
      n = length;
      longest = &in;
    } else if (length != n) {
      throw py::value_error(in.name + " has " + std::to_string(length) + " values but " +
                            longest->name + " has " + std::to_string(n) +
                            ": arrays broadcast only when their lengths are equal or 1");
    }
  }
  for (const Input& in : inputs) check_ranges(in);

  // The scene: the one given, or the keys the arguments give; each argument's first value set in.
  json doc;
  if (scene.is_none()) {
    bool rectangle = false;
    for (const Input& in : inputs) rectangle |= in.field == sw::length_m;
    doc = {{"name", "closed-forms"},
           {"landslide", {{"shape", {{"kind", rectangle ? "rectangle" : "front-body-tail"}}}}},
           {"barrier", json::object()}};
  } else {
    doc = scene_document(scene);
  }
  // The parser's default methods, written out: a coefficient given below then adds to them.
  if (doc.is_object() && !doc.contains("methods"))
    doc["methods"] = {{"empirical", json::object()}, {"analytical", json::object()}};
  if (!fixed.is_none()) {
    if (!py::isinstance<py::bool_>(fixed))
      throw py::type_error("fixed: a " + type_name(fixed) + ": give True or False");
    set_key(doc, "/barrier/fixed", fixed.cast<bool>());
  }
  Scene parsed;
  try {
    parsed = parse_scene(point_document(doc, inputs, 0));
  } catch (const InputError& e) {
    throw py::value_error(at_index(n, 0) + e.what());
  }
  bool empirical = false, analytical = false;
  for (const auto& m : only) (m == "empirical" ? empirical : analytical) = true;
  if (only.empty()) {
    empirical = parsed.methods.empirical.has_value();
    analytical = parsed.methods.analytical.has_value();
    if (!empirical && !analytical)
      throw py::value_error(
          "methods: the scene selects no closed form (methods.empirical, methods.analytical): "
          "give methods=\"empirical\", \"analytical\" or both");
  }

  KernelOutput k;
  if (n > 0) k = evaluate(scene_values(parsed), inputs, n, empirical, analytical);
  for (std::size_t i = 0; i < n; ++i) {
    const int bad = k.invalid_field[i];
    if (bad < 0) continue;
    std::string reason;
    try {
      parse_scene(point_document(doc, inputs, i));
    } catch (const InputError& e) {
      reason = e.what();
    }
    if (reason.empty())  // the kernel's check and the scene parser disagree: a bug
      reason = std::string("rejected by the sweep's range check at ") +
               sw::scene_field_pointer[bad] + " but accepted by the scene parser";
    throw py::value_error(at_index(n, i) + reason);
  }

  py::dict result;
  for (int m = 0; m < 2; ++m) {
    if (!(m == 0 ? empirical : analytical)) continue;
    py::dict outputs;
    for (int o = 0; o < kOutputs; ++o) {
      const double* column = k.values.data() + (m * kOutputs + o) * n;
      outputs[sw::closed_form_output_name[o]] = py::array_t<double>(n, column);
    }
    result[m == 0 ? "empirical" : "analytical"] = outputs;
  }
  return result;
}

// The docstring's table of keyword arguments: name, scene key, allowed range.
std::string input_table() {
  std::string out;
  for (int f = 0; f < sw::scene_field_count; ++f) {
    if (mpm_only(f)) continue;
    std::string requirement =
        f == sw::top_width_m ? "must be in [0, base_width_m]" : scene_field_requirement(f);
    out += "    " + std::string(sw::scene_field_name[f]) + " (" + sw::scene_field_pointer[f] +
           "): " + requirement.substr(8) + "\n";
  }
  return out;
}

}  // namespace

void add_closed_forms(py::module_& m) {
  const std::string fields_doc =
      "The keyword arguments are numeric fields of the scene, named as below (the unit is in the\n"
      "name: m, m/s, kg/m^3, kg/m, deg; the others are dimensionless), each a number or a 1-D\n"
      "array of float64; arrays broadcast (every length is n or 1) and the result has n values\n"
      "per output. Each replaces its key (scene key, allowed range):\n\n" +
      input_table() +
      "\nscene: a dict (the JSON of a scene file) or the path of a scene file; it gives the\n"
      "fields not given as arguments and what is not a number (the landslide's shape, whether\n"
      "the barrier is given by its density or its mass, barrier_model, a dry MPM landslide).\n"
      "Without it the arguments must give every required key (thickness_m, velocity_m_s,\n"
      "density_kg_m3, body_squares or length_m, height_m, base_width_m, top_width_m,\n"
      "face_angle_deg, barrier_density_kg_m3 or barrier_mass_kg_per_m), and the landslide is\n"
      "a rectangle exactly when length_m is given. fixed: True or False sets barrier.fixed.\n\n"
      "Outputs, per method, arrays of n values: peak_force (N/m, normal to the face, per metre\n"
      "of barrier width), rise_time (s, T1), impact_duration (s, T2), final_displacement (m,\n"
      "the barrier's; 0 for a fixed barrier, inf if it never stops).\n\n"
      "Raises ValueError naming the field, the index and the value, with its allowed range\n"
      "(`thickness_m[3] = -1: must be > 0`), or the scene parser's message for the scene at\n"
      "that index (`index 3: barrier.top_width_m = 3: must be in [0, base_width_m = 2] (m)`);\n"
      "TypeError for an unknown keyword.";
  const std::string doc =
      "closed_forms(scene=None, methods=None, fixed=None, **fields) -> dict\n\n"
      "The empirical (Di Perna et al. 2022) and analytical two-body (Cuomo et al. 2022) models\n"
      "for arrays of scene fields, in one call of the batched kernel of `lsi sweep`; the same\n"
      "values as `lsi run` on the scene of each index.\n\n"
      "methods: \"empirical\", \"analytical\" or both (a list or \"empirical,analytical\"); by\n"
      "default the closed forms the scene selects. Returns {method: {output: array}}.\n\n" +
      fields_doc;
  m.def("closed_forms", &closed_forms, doc.c_str(), py::arg("scene") = py::none(),
        py::arg("methods") = py::none(), py::arg("fixed") = py::none());
  for (const char* method : {"empirical", "analytical"}) {
    const std::string one =
        std::string(method) + "(scene=None, fixed=None, **fields) -> dict\n\n" +
        (std::string(method) == "empirical"
             ? "The empirical model (Di Perna et al. 2022): Froude-based peak force, triangular\n"
               "pulse and, for a free barrier, its sliding under that pulse.\n"
             : "The analytical two-body model (Cuomo et al. 2022): inelastic collision (lambda,\n"
               "tau), the pulse and the barrier's displacement with base friction.\n") +
        "closed_forms(scene, \"" + method + "\", fixed, **fields)[\"" + method +
        "\"]: {output: array}.\n\n" + fields_doc;
    m.def(
        method,
        [method](py::handle scene, py::handle fixed, const py::kwargs& fields) {
          return py::object(closed_forms(scene, py::str(method), fixed, fields)[method]);
        },
        one.c_str(), py::arg("scene") = py::none(), py::arg("fixed") = py::none());
  }
  py::dict inputs;
  for (int f = 0; f < sw::scene_field_count; ++f)
    if (!mpm_only(f)) inputs[sw::scene_field_name[f]] = sw::scene_field_pointer[f];
  m.attr("closed_form_inputs") = inputs;
}

}  // namespace lsi::python
