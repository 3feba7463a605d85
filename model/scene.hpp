// The scene: a landslide, a barrier and the methods to run, as read from a scene file
// (io/scene_parser.hpp). The key names are the public contract and are documented in
// docs/reference/scene_schema.md (the one place where the schema is described).
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/inertial_friction_input.hpp"
#include "model/input_error.hpp"
#include "model/mpm_settings.hpp"

namespace lsi {

struct LandslideShape {
  enum class Kind { FrontBodyTail, Rectangle };
  Kind kind = Kind::FrontBodyTail;
  int body_squares = 4;   // front-body-tail: number i of h x h squares between front and tail
  double length_m = 0.0;  // rectangle: its length
};

// Material of the landslide mixture; only the MPM uses it. Defaults: the paper's section 4.1.
struct LandslideMaterial {
  double porosity = 0.5;
  double friction_angle_deg = 20.0;
  double cohesion_kpa = 0.0;
  double young_modulus_mpa = 2.0;
  double poisson_ratio = 0.25;
  double hydraulic_conductivity_m_s = 1e-4;
  double liquid_bulk_modulus_mpa = 30.0;
  double liquid_viscosity_kpa_s = 1e-6;
  // mu(I) (optional): friction_angle_deg is then the static angle.
  std::optional<InertialFrictionInput> inertial_friction;
};

struct SceneLandslide {
  double thickness_m = 0.0;    // h
  double velocity_m_s = 0.0;   // v0 = v1,0, horizontal approach velocity
  double density_kg_m3 = 0.0;  // rho_m, mixture density
  LandslideShape shape;
  LandslideMaterial material;
  // tan(phi_b): Coulomb friction of the flow on its base (the paper's F1, Fig. 1); 0 is the
  // paper's smooth base. The MPM applies it to the skeleton's contact force with the base; the
  // momentum-consistent closed forms to the flow's weight, as that force (docs/theory/models.md).
  double base_friction = 0.0;
  // Derived from shape: L1,0 (equivalent length, m) and cross-section area (m^2).
  double equivalent_length_m() const;
  double area_m2() const;
  double mass_kg_per_m() const { return density_kg_m3 * area_m2(); }
};

struct SceneBarrier {
  double height_m = 0.0;      // H
  double base_width_m = 0.0;  // B
  double top_width_m = 0.0;   // b
  double face_angle_deg =
      90.0;  // beta, inclination of the impacted (upstream) face from horizontal
  std::optional<double> density_kg_m3;  // exactly one of density and mass_kg_per_m is given
  std::optional<double> mass_kg_per_m;
  double base_friction = 0.5;  // tan(delta_b)
  double face_friction = 0.3;  // tan(delta)
  bool fixed = false;
  double area_m2() const { return 0.5 * (base_width_m + top_width_m) * height_m; }
  double mass() const { return mass_kg_per_m ? *mass_kg_per_m : *density_kg_m3 * area_m2(); }
};

// How a closed form moves a free barrier: the paper's construction ("paper": the two-body pulse
// with base friction, or the rigid block under the empirical fixed-barrier pulse) or the
// momentum-consistent barrier pushed by the flow at their relative velocity ("momentum",
// kernels/closed_form/momentum_barrier.hpp; docs/theory/models.md).
enum class BarrierModel { Paper, Momentum };

// Method blocks: present means "run this method"; their keys override model parameters.
struct EmpiricalParameters {
  double a1 = 1.781;
  double a2 = -0.515;
  double tau = 0.14;
  double kappa = 0.0;
  BarrierModel barrier_model = BarrierModel::Paper;
};
struct AnalyticalParameters {
  // Defaults: "paper" 0.72 / 0.17 for a fixed barrier and 0.41 / 0.25 for a free one;
  // "momentum" 0.72 / 0.17 for both (its pulse is the fixed barrier's; the barrier's motion is
  // modelled, not calibrated into lambda and tau).
  std::optional<double> lambda;
  std::optional<double> tau;
  BarrierModel barrier_model = BarrierModel::Paper;
};
// Literature peak-force families with user-given coefficients (docs/theory/models.md, "Literature
// peak-force families").
struct LiteratureParameters {
  std::string family = "mixed";  // "hydrostatic" | "hydrodynamic" | "mixed"
  std::optional<double> hydrostatic_k;
  std::optional<double> hydrodynamic_alpha;
};

struct SceneMethods {
  std::optional<EmpiricalParameters> empirical;
  std::optional<AnalyticalParameters> analytical;
  std::optional<LiteratureParameters> literature;
  std::optional<MpmSettings> mpm;  // the `methods.mpm` block, parsed
};

struct Scene {
  std::string name;
  SceneLandslide landslide;
  SceneBarrier barrier;
  SceneMethods methods;
  nlohmann::json source;  // the scene as read (stored in the HDF5 root attribute `scene`)
};

}  // namespace lsi
