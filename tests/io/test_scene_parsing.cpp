// Scene parsing and validation (model/scene.hpp): the reference study files, derived values,
// defaults, and one-line InputError messages naming the JSON path, the value and the range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "model/mpm_impact.hpp"
#include "io/mpm_scene.hpp"
#include "model/scene.hpp"
#include "io/scene_parser.hpp"

namespace {

using lsi::InputError;
using lsi::Scene;
using nlohmann::json;
namespace fs = std::filesystem;

// This file is tests/io/test_scene_parsing.cpp: three levels up is the source root.
const fs::path kScenes = fs::path(__FILE__).parent_path().parent_path().parent_path() / "scenes";

// A valid scene (L1-B1 without the optional blocks); the bad-input tests mutate it.
json base_scene() {
  return json::parse(R"({
    "name": "L1-B1",
    "landslide": { "thickness_m": 2.0, "velocity_m_s": 6, "density_kg_m3": 1800,
                   "shape": {"kind": "front-body-tail", "body_squares": 6} },
    "barrier": { "height_m": 4, "base_width_m": 2.0, "top_width_m": 1.0, "face_angle_deg": 80,
                 "density_kg_m3": 2400 },
    "methods": { "empirical": {}, "analytical": {} }
  })");
}

json with(json j, const std::string& pointer, json value) {
  j[json::json_pointer(pointer)] = std::move(value);
  return j;
}

json without(json j, const std::string& pointer) {
  const json::json_pointer p(pointer);
  j[p.parent_pointer()].erase(p.back());
  return j;
}

// The InputError message of parse(j) (parse_scene for error_of); fails the test when nothing
// (or something else) is thrown, and checks the message is one line.
template <class Parse>
std::string input_error_of(const Parse& parse, const json& j) {
  try {
    parse(j);
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "message is not one line: " << m;
    return m;
  }
  ADD_FAILURE() << "no InputError for " << j.dump();
  return "<no error>";
}

std::string error_of(const json& j) {
  return input_error_of([](const json& x) { (void)lsi::parse_scene(x); }, j);
}

std::string load_error_of(const std::string& path) {
  try {
    (void)lsi::load_scene(path);
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "message is not one line: " << m;
    return m;
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "<no error>";
}

// Writes `text` to a fresh temporary file, removed on destruction.
class TempFile {
 public:
  explicit TempFile(const std::string& text) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("lsi_scene_" + std::string(info->name()) + "_" +
             std::to_string(reinterpret_cast<std::uintptr_t>(this)) + ".json");
    std::ofstream(path_) << text;
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

// ---- valid scenes -----------------------------------------------------------------------------

struct Landslide {
  const char* id;
  double h, v;
  int squares;
};
struct Barrier {
  const char* id;
  double beta, H, B, b, rho;
};
const Landslide kLandslides[] = {{"L1", 2.0, 6.0, 6}, {"L2", 2.5, 9.0, 6}, {"L3", 3.0, 12.5, 4}};
const Barrier kBarriers[] = {
    {"B1", 80, 4, 4.0, 1.5, 2400}, {"B2", 70, 5, 6.0, 2.0, 1800}, {"B3", 60, 5, 13.4, 3.0, 2000}};

// The reference study (README, "The reference study"): nine landslide-barrier cases, each with a
// free barrier (Lx-By) and a fixed copy (Lx-By-fixed).
TEST(SceneReference, AllEighteenFilesParseWithTheStudyValues) {
  int parsed = 0;
  for (const bool fixed : {false, true})
    for (const auto& l : kLandslides) {
      for (const auto& b : kBarriers) {
        const std::string name = std::string(l.id) + "-" + b.id + (fixed ? "-fixed" : "");
        SCOPED_TRACE(name);
        const Scene s = lsi::load_scene((kScenes / "reference" / (name + ".json")).string());
        EXPECT_EQ(s.name, name);
        EXPECT_DOUBLE_EQ(s.landslide.thickness_m, l.h);
        EXPECT_DOUBLE_EQ(s.landslide.velocity_m_s, l.v);
        EXPECT_DOUBLE_EQ(s.landslide.density_kg_m3, 1800.0);
        EXPECT_EQ(s.landslide.shape.kind, lsi::LandslideShape::Kind::FrontBodyTail);
        EXPECT_EQ(s.landslide.shape.body_squares, l.squares);
        EXPECT_DOUBLE_EQ(s.landslide.equivalent_length_m(), (2 + l.squares) * l.h);
        EXPECT_DOUBLE_EQ(s.landslide.area_m2(), (2 + l.squares) * l.h * l.h);
        EXPECT_DOUBLE_EQ(s.landslide.material.porosity, 0.5);
        EXPECT_DOUBLE_EQ(s.landslide.material.friction_angle_deg, 20.0);
        EXPECT_DOUBLE_EQ(s.landslide.material.hydraulic_conductivity_m_s, 1e-4);
        EXPECT_DOUBLE_EQ(s.landslide.material.liquid_viscosity_kpa_s, 1e-6);
        EXPECT_DOUBLE_EQ(s.barrier.face_angle_deg, b.beta);
        EXPECT_DOUBLE_EQ(s.barrier.height_m, b.H);
        EXPECT_DOUBLE_EQ(s.barrier.base_width_m, b.B);
        EXPECT_DOUBLE_EQ(s.barrier.top_width_m, b.b);
        ASSERT_TRUE(s.barrier.density_kg_m3.has_value());
        EXPECT_DOUBLE_EQ(*s.barrier.density_kg_m3, b.rho);
        EXPECT_FALSE(s.barrier.mass_kg_per_m.has_value());
        EXPECT_DOUBLE_EQ(s.barrier.mass(), b.rho * 0.5 * (b.B + b.b) * b.H);
        EXPECT_DOUBLE_EQ(s.barrier.base_friction, 0.5);
        EXPECT_DOUBLE_EQ(s.barrier.face_friction, 0.3);
        EXPECT_EQ(s.barrier.fixed, fixed);
        // The closed forms move a free barrier by momentum (docs/theory/models.md).
        ASSERT_TRUE(s.methods.empirical.has_value());
        ASSERT_TRUE(s.methods.analytical.has_value());
        EXPECT_EQ(s.methods.empirical->barrier_model, lsi::BarrierModel::Momentum);
        EXPECT_EQ(s.methods.analytical->barrier_model, lsi::BarrierModel::Momentum);
        EXPECT_FALSE(s.methods.literature.has_value());
        // The MPM column of the study: saturated, APIC, 8 cells through the thickness, the flow's
        // base friction 0.2 (README; docs/vv/reference_convergence.md).
        ASSERT_TRUE(s.methods.mpm.has_value());
        EXPECT_DOUBLE_EQ(s.methods.mpm->cell_size_m, s.landslide.thickness_m / 8);
        EXPECT_TRUE(s.methods.mpm->saturated);
        EXPECT_TRUE(s.methods.mpm->apic);
        EXPECT_DOUBLE_EQ(s.landslide.base_friction, 0.2);
        EXPECT_EQ(s.source.at("name"), name);
        ++parsed;
      }
    }
  EXPECT_EQ(parsed, 18);
}

TEST(SceneReference, L1AndB1DerivedValues) {
  const Scene s = lsi::load_scene((kScenes / "reference" / "L1-B1.json").string());
  EXPECT_DOUBLE_EQ(s.landslide.equivalent_length_m(), 16.0);  // (2 + 6) * 2
  EXPECT_DOUBLE_EQ(s.landslide.area_m2(), 32.0);              // (2 + 6) * 2^2
  EXPECT_DOUBLE_EQ(s.landslide.mass_kg_per_m(), 57600.0);     // 1800 * 32
  EXPECT_DOUBLE_EQ(s.barrier.area_m2(), 11.0);                // (4 + 1.5) / 2 * 4
  EXPECT_DOUBLE_EQ(s.barrier.mass(), 26400.0);                // 2400 * 11
}

TEST(SceneExamples, MinimalGetsAllDefaults) {
  const Scene s = lsi::load_scene((kScenes / "examples" / "minimal.json").string());
  EXPECT_EQ(s.name, "minimal");
  const lsi::LandslideMaterial m = s.landslide.material;
  EXPECT_DOUBLE_EQ(m.porosity, 0.5);
  EXPECT_DOUBLE_EQ(m.friction_angle_deg, 20.0);
  EXPECT_DOUBLE_EQ(m.cohesion_kpa, 0.0);
  EXPECT_DOUBLE_EQ(m.young_modulus_mpa, 2.0);
  EXPECT_DOUBLE_EQ(m.poisson_ratio, 0.25);
  EXPECT_DOUBLE_EQ(m.hydraulic_conductivity_m_s, 1e-4);
  EXPECT_DOUBLE_EQ(m.liquid_bulk_modulus_mpa, 30.0);
  EXPECT_DOUBLE_EQ(m.liquid_viscosity_kpa_s, 1e-6);
  EXPECT_DOUBLE_EQ(s.barrier.base_friction, 0.5);
  EXPECT_DOUBLE_EQ(s.barrier.face_friction, 0.3);
  EXPECT_FALSE(s.barrier.fixed);
  // No "methods": empirical and analytical with their defaults.
  ASSERT_TRUE(s.methods.empirical.has_value());
  EXPECT_DOUBLE_EQ(s.methods.empirical->a1, 1.781);
  EXPECT_DOUBLE_EQ(s.methods.empirical->a2, -0.515);
  EXPECT_DOUBLE_EQ(s.methods.empirical->tau, 0.14);
  EXPECT_DOUBLE_EQ(s.methods.empirical->kappa, 0.0);
  ASSERT_TRUE(s.methods.analytical.has_value());
  EXPECT_FALSE(s.methods.analytical->lambda.has_value());
  EXPECT_FALSE(s.methods.analytical->tau.has_value());
  EXPECT_FALSE(s.methods.literature.has_value());
  EXPECT_FALSE(s.methods.mpm.has_value());
  EXPECT_FALSE(s.source.contains("methods"));  // source is the scene as read
}

TEST(SceneExamples, RectangleFixedWithMassPerMetre) {
  const Scene s = lsi::load_scene((kScenes / "examples" / "rectangle-fixed.json").string());
  EXPECT_EQ(s.landslide.shape.kind, lsi::LandslideShape::Kind::Rectangle);
  EXPECT_DOUBLE_EQ(s.landslide.equivalent_length_m(), 20.0);
  EXPECT_DOUBLE_EQ(s.landslide.area_m2(), 50.0);  // 20 * 2.5
  EXPECT_DOUBLE_EQ(s.landslide.mass_kg_per_m(), 90000.0);
  EXPECT_FALSE(s.barrier.density_kg_m3.has_value());
  EXPECT_DOUBLE_EQ(s.barrier.mass(), 14400.0);
  EXPECT_DOUBLE_EQ(s.barrier.face_angle_deg, 90.0);
  EXPECT_TRUE(s.barrier.fixed);
  ASSERT_TRUE(s.methods.analytical.has_value());
  EXPECT_DOUBLE_EQ(s.methods.analytical->lambda.value(), 0.72);
  EXPECT_DOUBLE_EQ(s.methods.analytical->tau.value(), 0.17);
}

TEST(SceneParse, OverridesAndOptionalMethods) {
  json j = base_scene();
  j["landslide"]["material"] = {{"porosity", 0.4}, {"cohesion_kpa", 5}};
  j["barrier"]["base_friction"] = 0.6;
  j["barrier"]["face_friction"] = 0;
  j["methods"] = json::parse(R"({
    "empirical": {"a1": 2.0, "a2": -0.4, "tau": 0.2, "kappa": 0.1},
    "analytical": {"lambda": 1},
    "literature": {"family": "hydrostatic", "hydrostatic_k": 1.5},
    "mpm": {"cell_size_m": 0.1, "phases": "dry"}
  })");
  const Scene s = lsi::parse_scene(j);
  EXPECT_DOUBLE_EQ(s.landslide.material.porosity, 0.4);
  EXPECT_DOUBLE_EQ(s.landslide.material.cohesion_kpa, 5.0);
  EXPECT_DOUBLE_EQ(s.landslide.material.friction_angle_deg, 20.0);  // default kept
  EXPECT_DOUBLE_EQ(s.barrier.base_friction, 0.6);
  EXPECT_DOUBLE_EQ(s.barrier.face_friction, 0.0);
  EXPECT_DOUBLE_EQ(s.methods.empirical->a1, 2.0);
  EXPECT_DOUBLE_EQ(s.methods.empirical->a2, -0.4);
  EXPECT_DOUBLE_EQ(s.methods.empirical->tau, 0.2);
  EXPECT_DOUBLE_EQ(s.methods.empirical->kappa, 0.1);
  EXPECT_DOUBLE_EQ(s.methods.analytical->lambda.value(), 1.0);
  EXPECT_FALSE(s.methods.analytical->tau.has_value());
  ASSERT_TRUE(s.methods.literature.has_value());
  EXPECT_EQ(s.methods.literature->family, "hydrostatic");
  EXPECT_DOUBLE_EQ(s.methods.literature->hydrostatic_k.value(), 1.5);
  EXPECT_FALSE(s.methods.literature->hydrodynamic_alpha.has_value());
  ASSERT_TRUE(s.methods.mpm.has_value());
  EXPECT_EQ(s.methods.mpm->cell_size_m, 0.1);
  EXPECT_FALSE(s.methods.mpm->saturated);
  EXPECT_EQ(s.source, j);
  // The block is checked when the scene is read, whichever methods then run.
  j["methods"]["mpm"] = {{"cell_size_m", 0.1}, {"anything", {1, 2}}};
  EXPECT_CONTAINS(error_of(j), "methods.mpm.anything: unknown key");
  j["methods"]["mpm"] = {{"cell_size_m", -0.1}};
  EXPECT_CONTAINS(error_of(j), "methods.mpm.cell_size_m = -0.1");
}

TEST(SceneParse, OnlyTheSelectedMethods) {
  const Scene s =
      lsi::parse_scene(with(base_scene(), "/methods", {{"analytical", json::object()}}));
  EXPECT_FALSE(s.methods.empirical.has_value());
  EXPECT_TRUE(s.methods.analytical.has_value());
}

TEST(SceneParse, LiteratureTakesUserGivenCoefficients) {
  // family defaults to "mixed", which uses both coefficients.
  const Scene s = lsi::parse_scene(
      with(base_scene(), "/methods",
           {{"literature", {{"hydrostatic_k", 1.0}, {"hydrodynamic_alpha", 1.5}}}}));
  ASSERT_TRUE(s.methods.literature.has_value());
  EXPECT_EQ(s.methods.literature->family, "mixed");
  EXPECT_DOUBLE_EQ(s.methods.literature->hydrostatic_k.value(), 1.0);
  EXPECT_DOUBLE_EQ(s.methods.literature->hydrodynamic_alpha.value(), 1.5);
  // A single-coefficient family needs only its own coefficient.
  const Scene h =
      lsi::parse_scene(with(base_scene(), "/methods",
                            {{"literature", {{"family", "hydrostatic"}, {"hydrostatic_k", 2}}}}));
  EXPECT_EQ(h.methods.literature->family, "hydrostatic");
  EXPECT_DOUBLE_EQ(h.methods.literature->hydrostatic_k.value(), 2.0);
  EXPECT_FALSE(h.methods.literature->hydrodynamic_alpha.has_value());
  const Scene d = lsi::parse_scene(
      with(base_scene(), "/methods",
           {{"literature", {{"family", "hydrodynamic"}, {"hydrodynamic_alpha", 3}}}}));
  EXPECT_EQ(d.methods.literature->family, "hydrodynamic");
  EXPECT_DOUBLE_EQ(d.methods.literature->hydrodynamic_alpha.value(), 3.0);
  EXPECT_FALSE(d.methods.literature->hydrostatic_k.has_value());
}

TEST(SceneParse, IntegralFloatBodySquaresAccepted) {
  const Scene s = lsi::parse_scene(with(base_scene(), "/landslide/shape/body_squares", 4.0));
  EXPECT_EQ(s.landslide.shape.body_squares, 4);
  EXPECT_DOUBLE_EQ(s.landslide.equivalent_length_m(), 12.0);
}

TEST(SceneParse, FaceRunOutExactlyAtTheLimitIsAccepted) {
  // H / tan(45 deg) = 1 m = B - b (up to rounding).
  json j = base_scene();
  j["barrier"]["height_m"] = 1.0;
  j["barrier"]["face_angle_deg"] = 45;
  const Scene s = lsi::parse_scene(j);
  EXPECT_DOUBLE_EQ(s.barrier.area_m2(), 1.5);
  // A vertical face with top == base (a rectangle) is valid as well.
  j["barrier"]["top_width_m"] = 2.0;
  j["barrier"]["face_angle_deg"] = 90;
  EXPECT_DOUBLE_EQ(lsi::parse_scene(j).barrier.area_m2(), 2.0);
}

TEST(SceneDocs, CompleteExampleInTheSchemaParses) {
  // The first ```json block of docs/reference/scene_schema.md must stay a valid scene.
  std::ifstream in(kScenes.parent_path() / "docs" / "reference" / "scene_schema.md");
  ASSERT_TRUE(in) << "docs/reference/scene_schema.md not found";
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t begin = doc.find("```json\n");
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = doc.find("```", begin + 8);
  ASSERT_NE(end, std::string::npos);
  const Scene s = lsi::parse_scene(json::parse(doc.substr(begin + 8, end - begin - 8)));
  EXPECT_EQ(s.name, "L3-B1");
  EXPECT_DOUBLE_EQ(s.landslide.equivalent_length_m(), 18.0);
  EXPECT_DOUBLE_EQ(s.landslide.mass_kg_per_m(), 97200.0);
  EXPECT_DOUBLE_EQ(s.methods.analytical->lambda.value(), 0.72);
  EXPECT_EQ(s.methods.literature->family, "mixed");
  EXPECT_TRUE(s.methods.literature->hydrostatic_k.has_value());
  EXPECT_TRUE(s.methods.literature->hydrodynamic_alpha.has_value());
}

// ---- bad inputs: unknown keys -----------------------------------------------------------------

TEST(SceneParse, BarrierModelOfTheClosedForms) {
  const Scene paper = lsi::parse_scene(base_scene());
  EXPECT_EQ(paper.methods.analytical->barrier_model, lsi::BarrierModel::Paper);
  EXPECT_EQ(paper.methods.empirical->barrier_model, lsi::BarrierModel::Paper);
  json j = with(with(base_scene(), "/methods/analytical/barrier_model", "momentum"),
                "/methods/empirical/barrier_model", "momentum");
  const Scene m = lsi::parse_scene(j);
  EXPECT_EQ(m.methods.analytical->barrier_model, lsi::BarrierModel::Momentum);
  EXPECT_EQ(m.methods.empirical->barrier_model, lsi::BarrierModel::Momentum);
  EXPECT_CONTAINS(error_of(with(base_scene(), "/methods/analytical/barrier_model", "newton")),
                  "methods.analytical.barrier_model = \"newton\"");
  // The momentum variant has no static load after the pulse.
  EXPECT_CONTAINS(error_of(with(with(base_scene(), "/methods/empirical/barrier_model", "momentum"),
                                "/methods/empirical/kappa", 0.5)),
                  "methods.empirical.kappa = 0.5: must be 0 with \"barrier_model\": \"momentum\"");
}

TEST(SceneErrors, UnknownTopLevelKey) {
  EXPECT_EQ(error_of(with(base_scene(), "/nme", "x")),
            "nme: unknown key (allowed: name, landslide, barrier, methods)");
}

TEST(SceneErrors, UnknownLandslideKey) {
  json j = without(base_scene(), "/landslide/thickness_m");
  j["landslide"]["thicknes_m"] = 2.0;
  EXPECT_EQ(error_of(j),
            "landslide.thicknes_m: unknown key (allowed: thickness_m, velocity_m_s, density_kg_m3, "
            "shape, material, base_friction)");
}

TEST(SceneErrors, UnknownShapeKey) {
  const std::string m = error_of(with(base_scene(), "/landslide/shape/sides", 3));
  EXPECT_CONTAINS(m, "landslide.shape.sides: unknown key (allowed: kind, body_squares, length_m)");
}

TEST(SceneErrors, UnknownMaterialKey) {
  const std::string m = error_of(with(base_scene(), "/landslide/material", {{"porosty", 0.5}}));
  EXPECT_CONTAINS(m, "landslide.material.porosty: unknown key");
  EXPECT_CONTAINS(m, "porosity");
}

TEST(SceneErrors, UnknownBarrierKey) {
  const std::string m = error_of(with(base_scene(), "/barrier/hieght_m", 4));
  EXPECT_CONTAINS(m, "barrier.hieght_m: unknown key (allowed: height_m, base_width_m");
}

TEST(SceneErrors, UnknownMethodParameterKeys) {
  EXPECT_CONTAINS(error_of(with(base_scene(), "/methods/empirical/a3", 1)),
                  "methods.empirical.a3: unknown key (allowed: a1, a2, tau, kappa, barrier_model)");
  EXPECT_CONTAINS(error_of(with(base_scene(), "/methods/analytical/lamda", 0.5)),
                  "methods.analytical.lamda: unknown key (allowed: lambda, tau, barrier_model)");
  EXPECT_CONTAINS(error_of(with(base_scene(), "/methods/literature",
                                {{"hydrostatic_k", 1}, {"hydrodynamic_alpha", 1}, {"k", 1}})),
                  "methods.literature.k: unknown key");
}

TEST(SceneErrors, UnknownMethod) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods/ml", json::object())),
            "methods.ml: unknown key (allowed: empirical, analytical, literature, mpm)");
}

TEST(SceneErrors, OddKeyIsQuotedInThePath) {
  EXPECT_CONTAINS(error_of(with(base_scene(), "/barrier/height m", 4)),
                  "barrier[\"height m\"]: unknown key");
}

// ---- missing keys -----------------------------------------------------------------------------

TEST(SceneErrors, MissingBarrierHeight) {
  EXPECT_EQ(error_of(without(base_scene(), "/barrier/height_m")),
            "barrier.height_m: missing (required: number > 0, m)");
}

TEST(SceneErrors, MissingNameLandslideShapeAndKind) {
  EXPECT_EQ(error_of(without(base_scene(), "/name")), "name: missing (required: non-empty string)");
  EXPECT_EQ(error_of(without(base_scene(), "/landslide")), "landslide: missing (required: object)");
  EXPECT_EQ(error_of(without(base_scene(), "/landslide/shape")),
            "landslide.shape: missing (required: object)");
  EXPECT_EQ(error_of(without(base_scene(), "/landslide/shape/kind")),
            "landslide.shape.kind: missing (required: one of \"front-body-tail\", \"rectangle\")");
  EXPECT_EQ(error_of(without(base_scene(), "/landslide/shape/body_squares")),
            "landslide.shape.body_squares: missing (required: integer in [0, 1000000])");
}

TEST(SceneErrors, MissingTopWidthNamesTheBaseWidth) {
  EXPECT_EQ(error_of(without(base_scene(), "/barrier/top_width_m")),
            "barrier.top_width_m: missing (required: number in [0, base_width_m = 2], m)");
}

// ---- wrong types and non-finite numbers -------------------------------------------------------

TEST(SceneErrors, NumberAsString) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/velocity_m_s", "12")),
            "landslide.velocity_m_s = \"12\": must be a number");
}

TEST(SceneErrors, NumberAsBoolAndNull) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/thickness_m", true)),
            "landslide.thickness_m = true: must be a number");
  EXPECT_EQ(error_of(with(base_scene(), "/barrier/face_angle_deg", nullptr)),
            "barrier.face_angle_deg = null: must be a number");
}

TEST(SceneErrors, WrongTypesForStringsBoolsAndObjects) {
  EXPECT_EQ(error_of(with(base_scene(), "/name", 3)), "name = 3: must be a string");
  EXPECT_EQ(error_of(with(base_scene(), "/name", "")), "name = \"\": must be a non-empty string");
  EXPECT_EQ(error_of(with(base_scene(), "/barrier/fixed", "yes")),
            "barrier.fixed = \"yes\": must be a boolean (true or false)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide", 3)), "landslide = 3: must be an object");
  EXPECT_EQ(error_of(with(base_scene(), "/methods/empirical", true)),
            "methods.empirical = true: must be an object");
  EXPECT_EQ(error_of(with(base_scene(), "/methods/mpm", json::array({1}))),
            "methods.mpm = [1]: must be an object");
}

TEST(SceneErrors, TopLevelNotAnObject) {
  EXPECT_CONTAINS(error_of(json::array({1, 2})),
                  "(top level) = [1,2]: a scene must be a JSON object");
}

TEST(SceneErrors, NonFiniteNumbers) {
  // A 1e999 literal is a load_scene error (see SceneLoad.HugeExponentInFile); a DOM built in code
  // can still hold infinities and NaN.
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/thickness_m",
                          std::numeric_limits<double>::infinity())),
            "landslide.thickness_m = inf: must be finite");
  EXPECT_EQ(
      error_of(with(base_scene(), "/barrier/height_m", -std::numeric_limits<double>::infinity())),
      "barrier.height_m = -inf: must be finite");
  EXPECT_EQ(error_of(with(base_scene(), "/methods/empirical/tau",
                          std::numeric_limits<double>::quiet_NaN())),
            "methods.empirical.tau = nan: must be finite");
}

// ---- out-of-range values ----------------------------------------------------------------------

TEST(SceneErrors, NegativeAndZeroThickness) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/thickness_m", -3)),
            "landslide.thickness_m = -3: must be > 0 (m)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/thickness_m", 0)),
            "landslide.thickness_m = 0: must be > 0 (m)");
}

TEST(SceneErrors, OtherLandslideRanges) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/velocity_m_s", -1.5)),
            "landslide.velocity_m_s = -1.5: must be > 0 (m/s)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/density_kg_m3", 0)),
            "landslide.density_kg_m3 = 0: must be > 0 (kg/m^3)");
}

TEST(SceneErrors, MaterialRanges) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/material", {{"porosity", 1}})),
            "landslide.material.porosity = 1: must be in (0, 1)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/material", {{"poisson_ratio", 0.5}})),
            "landslide.material.poisson_ratio = 0.5: must be in (-1, 0.5)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/material", {{"friction_angle_deg", 90}})),
            "landslide.material.friction_angle_deg = 90: must be in [0, 90) (deg)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/material", {{"cohesion_kpa", -1}})),
            "landslide.material.cohesion_kpa = -1: must be >= 0 (kPa)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/material", {{"liquid_viscosity_kpa_s", 0}})),
            "landslide.material.liquid_viscosity_kpa_s = 0: must be > 0 (kPa s)");
}

// mu(I) in an impact scene's landslide: the same block as in an mpm_case material
// (model/inertial_friction_input.hpp), carried into the MPM material in SI units.
json landslide_with_inertial_friction() {
  return with(with(base_scene(), "/landslide/material",
                   {{"friction_angle_deg", 25},
                    {"inertial_friction",
                     {{"limit_friction_angle_deg", 38},
                      {"reference_inertial_number", 0.3},
                      {"grain_diameter_mm", 10},
                      {"grain_density_kg_m3", 2650}}}}),
              "/methods/mpm", {{"cell_size_m", 0.5}, {"end_time_s", 1}});
}

// The MPM material of a parsed inertial_friction block, in SI units (angles given in degrees).
void expect_inertial_friction(const lsi::mpm::Material& m, double static_deg, double limit_deg,
                              double I0, double grain_diameter_m, double grain_density) {
  const double deg = 3.14159265358979323846 / 180;
  EXPECT_TRUE(m.rate_dependent());
  EXPECT_DOUBLE_EQ(m.friction_angle, static_deg * deg);
  EXPECT_DOUBLE_EQ(m.limit_friction_angle, limit_deg * deg);
  EXPECT_DOUBLE_EQ(m.reference_inertial_number, I0);
  EXPECT_DOUBLE_EQ(m.grain_diameter, grain_diameter_m);
  EXPECT_DOUBLE_EQ(m.grain_density, grain_density);
}

TEST(SceneParse, LandslideInertialFrictionInSiUnits) {
  const Scene s = lsi::parse_scene(landslide_with_inertial_friction());
  ASSERT_TRUE(s.landslide.material.inertial_friction.has_value());
  EXPECT_DOUBLE_EQ(s.landslide.material.inertial_friction->limit_friction_angle_deg, 38);
  const lsi::MpmCase c = lsi::impact_case(s);
  ASSERT_EQ(c.materials.size(), 1u);
  expect_inertial_friction(c.materials[0], 25, 38, 0.3, 10e-3, 2650);  // 25: the static angle
  // Without the block (and in the reference scenes) the landslide is rate-independent.
  const Scene plain = lsi::parse_scene(
      without(landslide_with_inertial_friction(), "/landslide/material/inertial_friction"));
  EXPECT_FALSE(plain.landslide.material.inertial_friction.has_value());
  EXPECT_FALSE(lsi::impact_case(plain).materials[0].rate_dependent());
  // The shipped example (scenes/examples/impact-mu-i.json, docs/reference/scene_schema.md) is rate-dependent.
  const Scene example = lsi::load_scene((kScenes / "examples" / "impact-mu-i.json").string());
  const auto mu_i = lsi::impact_case(example).materials[0];
  EXPECT_TRUE(mu_i.rate_dependent());
  EXPECT_DOUBLE_EQ(mu_i.grain_diameter, 10e-3);
}

TEST(SceneErrors, LandslideInertialFrictionNamesTheFieldValueAndRange) {
  const std::string f = "/landslide/material/inertial_friction/";
  EXPECT_EQ(error_of(with(landslide_with_inertial_friction(), f + "limit_friction_angle_deg", 20)),
            "landslide.material.inertial_friction.limit_friction_angle_deg = 20: must not be "
            "below friction_angle_deg (25, the static angle): friction rises with the inertial "
            "number");
  // The default static angle (20 deg) when the material does not give one.
  EXPECT_CONTAINS(
      error_of(without(with(landslide_with_inertial_friction(), f + "limit_friction_angle_deg", 15),
                       "/landslide/material/friction_angle_deg")),
      "limit_friction_angle_deg = 15: must not be below friction_angle_deg (20,");
  EXPECT_EQ(error_of(with(landslide_with_inertial_friction(), f + "limit_friction_angle_deg", 90)),
            "landslide.material.inertial_friction.limit_friction_angle_deg = 90: must be in "
            "[0, 90) (deg)");
  EXPECT_EQ(error_of(with(landslide_with_inertial_friction(), f + "reference_inertial_number", -1)),
            "landslide.material.inertial_friction.reference_inertial_number = -1: must be > 0");
  EXPECT_EQ(error_of(with(landslide_with_inertial_friction(), f + "grain_diameter_mm", 0)),
            "landslide.material.inertial_friction.grain_diameter_mm = 0: must be > 0 (mm)");
  EXPECT_CONTAINS(error_of(without(landslide_with_inertial_friction(), f + "grain_density_kg_m3")),
                  "landslide.material.inertial_friction.grain_density_kg_m3: missing");
  EXPECT_CONTAINS(error_of(with(landslide_with_inertial_friction(), f + "grain_size_mm", 1)),
                  "landslide.material.inertial_friction.grain_size_mm: unknown key");
}

TEST(SceneErrors, EmpiricalTauOutsideOpenUnitInterval) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods/empirical/tau", 1.0)),
            "methods.empirical.tau = 1.0: must be in (0, 1)");
  EXPECT_EQ(error_of(with(base_scene(), "/methods/empirical/tau", 0)),
            "methods.empirical.tau = 0: must be in (0, 1)");
}

TEST(SceneErrors, EmpiricalA1AndA2) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods/empirical/a1", 0)),
            "methods.empirical.a1 = 0: must be > 0");
  EXPECT_EQ(error_of(with(base_scene(), "/methods/empirical/a2", 6)),
            "methods.empirical.a2 = 6: must be in [-5, 5]");
}

TEST(SceneErrors, AnalyticalTauOutsideOpenUnitInterval) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods/analytical/tau", 1.2)),
            "methods.analytical.tau = 1.2: must be in (0, 1)");
}

TEST(SceneErrors, AnalyticalLambdaNotPositive) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods/analytical/lambda", 0)),
            "methods.analytical.lambda = 0: must be in (0, 1]");
  EXPECT_EQ(error_of(with(base_scene(), "/methods/analytical/lambda", -0.1)),
            "methods.analytical.lambda = -0.1: must be in (0, 1]");
  EXPECT_EQ(error_of(with(base_scene(), "/methods/analytical/lambda", 1.01)),
            "methods.analytical.lambda = 1.01: must be in (0, 1]");
}

TEST(SceneErrors, FaceAngleZeroAnd95) {
  EXPECT_EQ(error_of(with(base_scene(), "/barrier/face_angle_deg", 0)),
            "barrier.face_angle_deg = 0: must be in (0, 90] (deg)");
  EXPECT_EQ(error_of(with(base_scene(), "/barrier/face_angle_deg", 95)),
            "barrier.face_angle_deg = 95: must be in (0, 90] (deg)");
}

TEST(SceneErrors, DensityAndMassBoth) {
  const std::string m = error_of(with(base_scene(), "/barrier/mass_kg_per_m", 14400));
  EXPECT_CONTAINS(m, "barrier.density_kg_m3 = 2400");
  EXPECT_CONTAINS(m, "barrier.mass_kg_per_m = 14400");
  EXPECT_CONTAINS(m, "exactly one of");
}

TEST(SceneErrors, DensityAndMassNeither) {
  const std::string m = error_of(without(base_scene(), "/barrier/density_kg_m3"));
  EXPECT_CONTAINS(m, "barrier.density_kg_m3 / barrier.mass_kg_per_m: missing");
  EXPECT_CONTAINS(m, "exactly one of density_kg_m3 > 0");
}

TEST(SceneErrors, BarrierMassNotPositive) {
  json j = without(base_scene(), "/barrier/density_kg_m3");
  j["barrier"]["mass_kg_per_m"] = -5;
  EXPECT_EQ(error_of(j), "barrier.mass_kg_per_m = -5: must be > 0 (kg/m)");
}

TEST(SceneErrors, TopWiderThanBase) {
  EXPECT_EQ(error_of(with(base_scene(), "/barrier/top_width_m", 3)),
            "barrier.top_width_m = 3: must be in [0, base_width_m = 2] (m)");
}

TEST(SceneErrors, NegativeFriction) {
  EXPECT_EQ(error_of(with(base_scene(), "/barrier/base_friction", -0.1)),
            "barrier.base_friction = -0.1: must be >= 0");
}

TEST(SceneErrors, FaceAngleInconsistentWithWidths) {
  // B1 with beta = 60: the face runs out 4 / tan(60) = 2.309 m > B - b = 1 m.
  const std::string m = error_of(with(base_scene(), "/barrier/face_angle_deg", 60));
  EXPECT_CONTAINS(m, "barrier.face_angle_deg = 60: the upstream face would run out");
  EXPECT_CONTAINS(m, "2.309 m but base_width_m - top_width_m = 1 m");
  EXPECT_CONTAINS(m, "face_angle_deg >= 75.96");  // atan(4 / 1)
}

TEST(SceneErrors, BodySquaresNotAnInteger) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/shape/body_squares", 2.5)),
            "landslide.shape.body_squares = 2.5: must be an integer");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/shape/body_squares", "4")),
            "landslide.shape.body_squares = \"4\": must be an integer");
}

TEST(SceneErrors, BodySquaresNegative) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/shape/body_squares", -1)),
            "landslide.shape.body_squares = -1: must be an integer in [0, 1000000]");
}

TEST(SceneErrors, RectangleWithoutLength) {
  json j = base_scene();
  j["landslide"]["shape"] = {{"kind", "rectangle"}};
  EXPECT_EQ(error_of(j), "landslide.shape.length_m: missing (required: number > 0, m)");
}

TEST(SceneErrors, ShapeKeysOfTheOtherKind) {
  json j = base_scene();
  j["landslide"]["shape"] = {{"kind", "rectangle"}, {"length_m", 10}, {"body_squares", 4}};
  EXPECT_EQ(error_of(j),
            "landslide.shape.body_squares = 4: not allowed when kind = \"rectangle\" (allowed: "
            "kind, length_m)");
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/shape/length_m", 10)),
            "landslide.shape.length_m = 10: not allowed when kind = \"front-body-tail\" (allowed: "
            "kind, body_squares)");
}

TEST(SceneErrors, UnknownShapeKind) {
  EXPECT_EQ(error_of(with(base_scene(), "/landslide/shape/kind", "square")),
            "landslide.shape.kind = \"square\": must be one of \"front-body-tail\", \"rectangle\"");
}

// ---- methods ----------------------------------------------------------------------------------

TEST(SceneErrors, EmptyMethods) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods", json::object())),
            "methods = {}: no method selected (allowed: empirical, analytical, literature, mpm)");
}

TEST(SceneErrors, LiteratureWithoutCoefficients) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods", {{"literature", json::object()}})),
            "methods.literature.hydrostatic_k: missing (required: number > 0 when family = "
            "\"mixed\")");
  EXPECT_CONTAINS(error_of(with(base_scene(), "/methods",
                                {{"literature", {{"family", "mixed"}, {"hydrostatic_k", 1}}}})),
                  "methods.literature.hydrodynamic_alpha: missing");
  EXPECT_CONTAINS(
      error_of(with(base_scene(), "/methods", {{"literature", {{"family", "hydrodynamic"}}}})),
      "methods.literature.hydrodynamic_alpha: missing");
}

TEST(SceneErrors, LiteraturePresetIsAnUnknownKey) {
  // No named coefficient set is shipped: `preset` is rejected like every unknown key.
  EXPECT_EQ(
      error_of(with(base_scene(), "/methods",
                    {{"literature",
                      {{"preset", "anything"}, {"hydrostatic_k", 1}, {"hydrodynamic_alpha", 1}}}})),
      "methods.literature.preset: unknown key (allowed: family, hydrostatic_k, "
      "hydrodynamic_alpha)");
  EXPECT_CONTAINS(
      error_of(with(base_scene(), "/methods", {{"literature", {{"preset", "anything"}}}})),
      "methods.literature.preset: unknown key");
}

TEST(SceneErrors, LiteratureBadFamilyBadCoefficientAndUnusedCoefficient) {
  EXPECT_EQ(error_of(with(base_scene(), "/methods", {{"literature", {{"family", "static"}}}})),
            "methods.literature.family = \"static\": must be one of \"hydrostatic\", "
            "\"hydrodynamic\", \"mixed\"");
  EXPECT_EQ(
      error_of(with(base_scene(), "/methods",
                    {{"literature", {{"family", "hydrodynamic"}, {"hydrodynamic_alpha", -1}}}})),
      "methods.literature.hydrodynamic_alpha = -1: must be > 0");
  EXPECT_EQ(error_of(with(
                base_scene(), "/methods",
                {{"literature",
                  {{"family", "hydrostatic"}, {"hydrostatic_k", 1}, {"hydrodynamic_alpha", 2}}}})),
            "methods.literature.hydrodynamic_alpha = 2: not used by family = \"hydrostatic\"");
  EXPECT_EQ(error_of(with(base_scene(), "/methods",
                          {{"literature", {{"hydrostatic_k", 0}, {"hydrodynamic_alpha", 1}}}})),
            "methods.literature.hydrostatic_k = 0: must be > 0");
}

// ---- load_scene: files and malformed JSON -----------------------------------------------------

TEST(SceneLoad, FileNotFoundNamesThePath) {
  const std::string path = (fs::temp_directory_path() / "lsi_no_such_scene.json").string();
  EXPECT_EQ(load_error_of(path), path + ": scene file not found");
}

TEST(SceneLoad, NaNLiteralReportsLineAndColumn) {
  const TempFile f(
      "{\n"
      "  \"name\": \"x\",\n"
      "  \"landslide\": {\"thickness_m\": NaN}\n"
      "}\n");
  const std::string m = load_error_of(f.path());
  EXPECT_CONTAINS(m, f.path() + ":3:32: malformed JSON: ");
  EXPECT_CONTAINS(m, "NaN and Infinity are not valid JSON");
}

TEST(SceneLoad, NegativeInfinityLiteral) {
  const TempFile f("{\"name\": -Infinity}");
  const std::string m = load_error_of(f.path());
  EXPECT_CONTAINS(m, f.path() + ":1:11: malformed JSON: ");
  EXPECT_CONTAINS(m, "NaN and Infinity are not valid JSON");
}

TEST(SceneLoad, MalformedJsonReportsLineAndColumn) {
  // Missing comma after "x" on line 2: the parser stops at the end of the "landslide" string.
  const TempFile f(
      "{\n"
      "  \"name\": \"x\"\n"
      "  \"landslide\": {}\n"
      "}\n");
  const std::string m = load_error_of(f.path());
  EXPECT_CONTAINS(m, f.path() + ":3:13: malformed JSON: syntax error");
  EXPECT_EQ(m.find("NaN"), std::string::npos) << m;
}

TEST(SceneLoad, EmptyFile) {
  const TempFile f("");
  EXPECT_CONTAINS(load_error_of(f.path()), f.path() + ":1:1: malformed JSON: ");
}

TEST(SceneLoad, HugeExponentInFileIsNotFinite) {
  const TempFile f(
      "{\n"
      "  \"name\": \"x\",\n"
      "  \"landslide\": {\"velocity_m_s\": 6, \"thickness_m\": 1e999}\n"
      "}\n");
  EXPECT_EQ(load_error_of(f.path()),
            f.path() +
                ":3:55: landslide.thickness_m = 1e999: must be finite (the number overflows "
                "a double)");
}

TEST(SceneLoad, HugeExponentInsideAnArrayNamesTheIndex) {
  const TempFile f("{\"methods\": {\"mpm\": {\"xs\": [1, 2, -1e400]}}}");
  EXPECT_CONTAINS(load_error_of(f.path()), "methods.mpm.xs[2] = -1e400: must be finite");
}

TEST(SceneLoad, DuplicateKey) {
  const TempFile f("{\"name\": \"a\", \"landslide\": {\"thickness_m\": 2, \"thickness_m\": 3}}");
  EXPECT_EQ(load_error_of(f.path()),
            f.path() + ": landslide.thickness_m: duplicate key (each key may appear only once)");
}

TEST(SceneLoad, TopLevelMustBeAnObject) {
  const TempFile f("[1, 2, 3]");
  EXPECT_EQ(load_error_of(f.path()), f.path() + ": the top level must be a JSON object, got array");
}

TEST(SceneLoad, ValidationErrorsComeThrough) {
  const TempFile f(with(base_scene(), "/landslide/thickness_m", -3).dump());
  EXPECT_EQ(load_error_of(f.path()), "landslide.thickness_m = -3: must be > 0 (m)");
}

// ---- MPM verification scenes (mpm_case): the mu(I) friction of a Mohr-Coulomb material ----

json granular_case() {
  return json::parse(R"({"name": "beads", "mpm_case": {
      "domain_m": {"x": [0, 1], "y": [0, 0.5]},
      "walls": {"bottom": {"position_m": 0.05, "no_slip": true}},
      "materials": {"beads": {"model": "mohr-coulomb", "density_kg_m3": 1470,
                              "young_modulus_mpa": 0.2, "poisson_ratio": 0.3,
                              "friction_angle_deg": 22.5,
                              "inertial_friction": {"limit_friction_angle_deg": 40,
                                                    "reference_inertial_number": 0.279,
                                                    "grain_diameter_mm": 0.5,
                                                    "grain_density_kg_m3": 2450}}},
      "bodies": [{"material": "beads", "polygon_m": [[0.1, 0.05], [0.3, 0.05], [0.3, 0.15], [0.1, 0.15]]}]},
    "methods": {"mpm": {"cell_size_m": 0.01, "end_time_s": 0.1}}})");
}

std::string mpm_case_error_of(const json& j) {
  return input_error_of([](const json& x) { (void)lsi::parse_mpm_case(x); }, j);
}

TEST(MpmCaseParse, InertialFrictionInSiUnits) {
  const lsi::MpmCase c = lsi::parse_mpm_case(granular_case());
  ASSERT_EQ(c.materials.size(), 1u);
  expect_inertial_friction(c.materials[0], 22.5, 40, 0.279, 0.5e-3, 2450);  // 22.5: static
  // Without the block the material is rate-independent.
  const lsi::MpmCase plain =
      lsi::parse_mpm_case(without(granular_case(), "/mpm_case/materials/beads/inertial_friction"));
  EXPECT_FALSE(plain.materials[0].rate_dependent());
}

TEST(MpmCaseErrors, InertialFrictionNamesTheFieldValueAndRange) {
  const std::string f = "/mpm_case/materials/beads/inertial_friction/";
  EXPECT_CONTAINS(mpm_case_error_of(with(granular_case(), f + "limit_friction_angle_deg", 20)),
                  "mpm_case.materials.beads.inertial_friction.limit_friction_angle_deg = 20: "
                  "must not be below friction_angle_deg (22.5");
  EXPECT_CONTAINS(mpm_case_error_of(with(granular_case(), f + "reference_inertial_number", 0)),
                  "mpm_case.materials.beads.inertial_friction.reference_inertial_number = 0: must "
                  "be > 0");
  EXPECT_CONTAINS(
      mpm_case_error_of(with(granular_case(), f + "grain_diameter_mm", -0.5)),
      "mpm_case.materials.beads.inertial_friction.grain_diameter_mm = -0.5: must be > 0");
  EXPECT_CONTAINS(mpm_case_error_of(with(granular_case(), f + "grain_density_kg_m3", "2450")),
                  "mpm_case.materials.beads.inertial_friction.grain_density_kg_m3");
  EXPECT_CONTAINS(mpm_case_error_of(without(granular_case(), f + "grain_density_kg_m3")),
                  "grain_density_kg_m3");
  EXPECT_CONTAINS(mpm_case_error_of(with(granular_case(), f + "grain_size_mm", 1)),
                  "mpm_case.materials.beads.inertial_friction.grain_size_mm: unknown key");
  // Only a Mohr-Coulomb material has a friction angle to make rate-dependent.
  json elastic = granular_case();
  auto& beads = elastic["mpm_case"]["materials"]["beads"];
  beads["model"] = "linear-elastic";
  beads.erase("friction_angle_deg");
  EXPECT_CONTAINS(mpm_case_error_of(elastic), "mpm_case.materials.beads.inertial_friction");
  EXPECT_CONTAINS(mpm_case_error_of(elastic), "mohr-coulomb");
}

}  // namespace
