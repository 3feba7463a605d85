#include "io/study_points.hpp"

#include <cmath>
#include <string>

#include "io/json_fields.hpp"
#include "io/study_parser.hpp"
#include "model/input_error.hpp"
#include "sweeps/sampled_scene.hpp"

namespace lsi {

std::string scene_field_requirement(int field) {
  const sweeps::FieldRange f = sweeps::scene_field_range(field);
  json_fields::Range r;
  if (std::isfinite(f.lo)) r.lo = json_fields::Bound{f.lo, f.lo_closed, {}};
  if (std::isfinite(f.hi)) r.hi = json_fields::Bound{f.hi, f.hi_closed, {}};
  return std::string("must be ") + (f.integer ? "an integer " : "") + r.describe();
}

void check_given_points(const Study& s, const PointsTable& t) {
  const std::size_t dims = s.inputs.size();
  // A key the closed forms' values do not hold (one of methods.mpm) is checked by the scene
  // parser on every row; the others by the sweep kernel's check, and by the parser on the first
  // row (that the scene takes the key at all) and on any row the kernel's check refuses.
  bool parse_every_row = false;
  for (const auto& in : s.inputs) parse_every_row |= in.field < 0;
  for (std::size_t i = 0; i < t.rows; ++i) {
    const double* x = s.points.value.data() + i * dims;
    sweeps::SceneValues v = s.base_values;
    for (std::size_t d = 0; d < dims; ++d)
      if (s.inputs[d].field >= 0) v.value[s.inputs[d].field] = x[d];
    const int bad = sweeps::first_invalid_field(v);
    if (bad < 0 && i > 0 && !parse_every_row) continue;
    for (std::size_t d = 0; d < dims && bad >= 0; ++d)
      if (s.inputs[d].field == bad && !sweeps::in_range(x[d], sweeps::scene_field_range(bad)))
        throw InputError(t.shown + ": " + t.where(i) + ", column " + s.inputs[d].path + " = " +
                         format_number(x[d]) + ": " + scene_field_requirement(bad));
    std::string reason = invalid_sample_reason(s, x);
    if (reason.empty() && bad >= 0)  // the kernel's check and the scene parser disagree: a bug
      reason = std::string("rejected by the sweep's range check at ") +
               sweeps::scene_field_pointer[bad] + " but accepted by the scene parser";
    if (!reason.empty())
      throw InputError(t.shown + ": " + t.where(i) +
                       ": the scene with this row is invalid: " + reason);
  }
}

}  // namespace lsi
