// XPBI's continua against what holds exactly: the tensor virial of a body at rest, the momentum
// of a free body, the permanent strain von Mises plasticity leaves, and bit-identical results on
// any thread count.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <random>
#include <string>

#include "moreau/continuum/continuum_stress.hpp"
#include "moreau/errors.hpp"
#include "moreau/model/diagnostics.hpp"
#include "moreau/scene/scene.hpp"
#include "continuum_test_helpers.hpp"

namespace moreau {
namespace {

void run(Scene& scene, Real duration, int threads = 1) {
  StageTimer timer;
  const long steps = std::lround(duration / scene.model.settings.dt);
  for (long k = 0; k < steps; ++k) scene.formulation->step(scene.model, scene.state, timer, threads);
}

std::string column_scene(const std::string& plasticity) {
  return fmt::format(R"({{"name": "column", "settings": {{"solver": "xpbi", "dt": 0.005, "substeps": 10, "iterations": 5}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.5}},
                  {{"name": "block", "kind": "continuum", "blocks": [{{"min": [-0.04, 0, -0.04], "max": [0.04, 0.16, 0.04]}}],
                    "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5, "poisson_ratio": 0.3{}}}]}})",
                     plasticity);
}

// A body at rest on the ground y = 0 under gravity g: integrating the equilibrium div sigma = rho g
// against y gives the tensor virial  int sigma_yy dV = -W (y_c - y_0), W its weight, y_c its
// centre of mass and y_0 where the ground's reaction acts (whatever its distribution, friction
// included). The particles' contacts hold their centres r/2 off the ground, so y_0 = r/2. With
// the engine's constraint forces the gradients of sum V^0 Psi(F), and the corrected kernel
// gradients exact for linear motions, the discrete body at rest satisfies it too: it checks that
// the forces are the StVK-Hencky stress's.
void expect_virial(Scene& scene, const char* what, Real settle_time) {
  run(scene, settle_time);
  Real W = 0;
  for (Index i = 0; i < scene.model.continuum.size(); ++i)
    W += 9.81 * scene.model.particle_mass[scene.model.continuum.particle[i]];
  const Real y_c = center_of_mass(scene.model, scene.state, 1).y();
  const Real expected = -W * (y_c - scene.model.continuum.spacing / 2);
  const Real measured = test::continuum_stress_integral(scene)(1, 1);
  fmt::print("{}: int sigma_yy dV = {:.6g} N m, -W (y_c - r/2) = {:.6g} N m, error {:.3g} %, kinetic {:.3g} J\n", what,
             measured, expected, 100 * (measured / expected - 1), kinetic_energy(scene.model, scene.state, 1));
  // 2 %: the issue's bound on the StVK-Hencky stress. What is left are the particles near the
  // surfaces, whose corrected gradients see one-sided neighbourhoods.
  EXPECT_NEAR(measured / expected, 1, 0.02) << what;
}

TEST(XpbiContinuum, AnElasticColumnAtRestCarriesItsWeightByTheHenckyStress) {
  Scene scene = load_scene_text(column_scene(""), "column");
  expect_virial(scene, "elastic column", 1.5);
}

TEST(XpbiContinuum, AFreeBodyKeepsItsMomentum) {
  Scene scene = load_scene_text(R"({"name": "free", "settings": {"solver": "xpbi", "dt": 0.005, "substeps": 10,
      "iterations": 5, "gravity": [0, 0, 0]},
      "objects": [{"name": "lump", "kind": "continuum", "blocks": [{"min": [0, 0, 0], "max": [0.08, 0.06, 0.07]}],
                   "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5,
                   "plasticity": {"model": "von_mises", "yield_stress": 2000}}]})",
                                "free");
  std::mt19937_64 draw(7);
  auto unit = [&] { return static_cast<Real>(draw() >> 11) * 0x1.0p-53 - 0.5; };
  for (Vec3& v : scene.state.velocity) v = Vec3(unit(), unit(), unit());
  const Vec3 p0 = linear_momentum(scene.model, scene.state, 0);
  const Vec3 L0 = angular_momentum(scene.model, scene.state, 0, Vec3::Zero());
  Real scale = 0;
  for (Index p = 0; p < scene.model.particle_count(); ++p) scale += scene.model.particle_mass[p] * scene.state.velocity[p].norm();
  run(scene, 0.5);
  const Vec3 p1 = linear_momentum(scene.model, scene.state, 0);
  const Vec3 L1 = angular_momentum(scene.model, scene.state, 0, Vec3::Zero());
  fmt::print("momentum change {:.3g} of sum m|v| {:.3g}; angular momentum {:.3g} -> {:.3g} (change {:.3g})\n",
             (p1 - p0).norm(), scale, L0.norm(), L1.norm(), (L1 - L0).norm());
  EXPECT_LT((p1 - p0).norm(), 5e-12 * scale);  // round-off of 1000 substeps
}

std::string sand_column(Real spacing) {
  return fmt::format(R"({{"name": "sand", "settings": {{"solver": "xpbi", "dt": 0.005, "substeps": 20, "iterations": 5}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.6}},
                  {{"name": "sand", "kind": "continuum", "cylinders": [{{"base": [0, 0, 0], "radius": 0.04, "height": 0.08}}],
                    "spacing": {}, "density": 1000, "youngs_modulus": 1e5, "friction": 0.6,
                    "plasticity": {{"model": "drucker_prager", "friction_angle_deg": 35}}}}]}})",
                     spacing);
}

// A collapsed sand column at rest: the same virial, now with the stresses inside the
// Drucker-Prager cone that the return map keeps them in.
TEST(XpbiContinuum, ACollapsedSandColumnAtRestCarriesItsWeightByItsStress) {
  Scene scene = load_scene_text(sand_column(0.01), "sand");
  expect_virial(scene, "sand pile", 0.6);
  // At rest: 1e-9 J is a speed of about 1 mm/s, far below the 0.5 m/s of the collapse.
  EXPECT_LT(kinetic_energy(scene.model, scene.state, 1), 1e-9);
}

TEST(XpbiContinuum, ResultsAreBitIdenticalOnAnyThreadCount) {
  Scene one = load_scene_text(sand_column(0.005), "sand"), two = load_scene_text(sand_column(0.005), "sand");
  run(one, 0.05, 1);
  run(two, 0.05, 2);
  EXPECT_TRUE(one.state.position == two.state.position);
  EXPECT_TRUE(one.state.velocity == two.state.velocity);
  EXPECT_TRUE(one.state.continuum.deformation == two.state.continuum.deformation);
  EXPECT_TRUE(one.state.continuum.plastic_strain == two.state.continuum.plastic_strain);
  Real moved = 0;
  for (Index p = 0; p < one.model.particle_count(); ++p)
    moved = std::max(moved, (one.state.position[p] - one.model.particle_rest_position[p]).norm());
  EXPECT_GT(moved, 0.005);  // the column is collapsing
}

// A block spinning freely at 10 rad/s about its centre. The constraints are isotropic and XSPH
// smooths only what departs from the particles' linear velocity field, so neither brakes a rigid
// spin; what is lost is the position-level scheme's: a body turned by D = omega h in a substep
// along the straight line x + h v is stretched by D^2 / 2, and pulling it back keeps (1 - D^2) of
// its spin (as shape matching does, docs/scene-format.md).
TEST(XpbiContinuum, ASpinningBodyLosesOnlyThePositionLevelSchemesShare) {
  Scene scene = load_scene_text(R"({"name": "spin", "settings": {"solver": "xpbi", "dt": 0.005, "substeps": 10,
      "iterations": 5, "gravity": [0, 0, 0]},
      "objects": [{"name": "lump", "kind": "continuum", "blocks": [{"min": [-0.04, -0.03, -0.035], "max": [0.04, 0.03, 0.035]}],
                   "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5}]})",
                                "spin");
  const Vec3 omega(0, 10, 0);
  for (Index p = 0; p < scene.model.particle_count(); ++p) scene.state.velocity[p] = omega.cross(scene.state.position[p]);
  const Vec3 L0 = angular_momentum(scene.model, scene.state, 0, Vec3::Zero());
  run(scene, 0.5);
  const Vec3 c = center_of_mass(scene.model, scene.state, 0);
  const Vec3 L1 = angular_momentum(scene.model, scene.state, 0, c);
  fmt::print("angular momentum {:.6g} -> {:.6g} ({:.4g} kept), off-axis {:.3g}\n", L0.y(), L1.y(), L1.y() / L0.y(),
             std::hypot(L1.x(), L1.z()));
  const Real D = 10 * 0.005 / 10, expected = std::pow(1 - D * D, 1000);
  // 0.2 %: the prediction is first order in D^2 and ignores the stretch the elastic rows leave; the
  // spin axis stays put but for round-off (1e-6 of the spin).
  EXPECT_NEAR(L1.y() / L0.y(), expected, 2e-3 * expected);
  EXPECT_LT(std::hypot(L1.x(), L1.z()), 1e-6 * L0.y());
}

// Uniaxial compression between frictionless plates past yield, then release: a von Mises solid
// keeps the total logarithmic strain less the elastic part sigma_Y / E it springs back by.
TEST(XpbiContinuum, VonMisesCompressionLeavesTheTotalStrainLessTheElasticPart) {
  Scene scene = load_scene_text(R"({"name": "press", "settings": {"solver": "xpbi", "dt": 0.01, "substeps": 20,
      "iterations": 5, "gravity": [0, 0, 0]},
      "objects": [{"name": "floor", "kind": "collider", "shape": {"type": "plane"}, "friction": 0},
                  {"name": "plate", "kind": "collider", "shape": {"type": "plane", "normal": [0, -1, 0], "point": [0, 0.1, 0]},
                   "velocity": [0, -0.05, 0], "until": 0.4, "friction": 0},
                  {"name": "block", "kind": "continuum", "blocks": [{"min": [-0.05, 0, -0.05], "max": [0.05, 0.1, 0.05]}],
                   "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5, "poisson_ratio": 0.3, "friction": 0,
                   "plasticity": {"model": "von_mises", "yield_stress": 1000}}]})",
                                "press");
  auto height = [&] {
    Real lo = 1e9, hi = -1e9;
    for (const Vec3& x : scene.state.position) lo = std::min(lo, x.y()), hi = std::max(hi, x.y());
    return hi - lo;
  };
  const Real h0 = height();
  run(scene, 0.4);
  const Real loaded = std::log(h0 / height());
  run(scene, 0.3);
  // Released, the block rings about its unloaded height: average over the next 0.3 s.
  Real mean_height = 0;
  for (int k = 0; k < 30; ++k) {
    run(scene, 0.01);
    mean_height += height() / 30;
  }
  const Real permanent = std::log(h0 / mean_height), springback = loaded - permanent, elastic = 1000 / 1e5;
  fmt::print("compressed {:.4f}, permanent {:.4f}, springback {:.4f} against sigma_Y / E = {:.4f} ({:.3g} %)\n",
             loaded, permanent, springback, elastic, 100 * (springback / elastic - 1));
  EXPECT_NEAR(permanent / (loaded - elastic), 1, 0.05);  // the issue's bound on the permanent strain
  // The springback alone, 4 % of the total strain, comes out 33 % above sigma_Y / E (0.0133
  // against 0.0100). Read from the particles' positions, it carries their disagreement with the
  // deformation gradients, which is a few percent of the strain (XpbiElastic's compressed cube:
  // its whole height's strain 8 % short of the strain its particles hold). This bound, 2 % of the
  // total strain (1.3 % measured), keeps it from growing unnoticed; it does not validate it.
  EXPECT_LT(std::abs(springback - elastic), 0.02 * loaded);
}

// Bad input names its JSON path and what is allowed; the formulations without continua name xpbi.
TEST(XpbiContinuum, BadInputNamesItsPath) {
  auto scene = [](const std::string& solver, const std::string& keys) {
    return fmt::format(R"({{"name": "bad", "settings": {{"solver": "{}"}},
        "objects": [{{"name": "a", "kind": "continuum", "blocks": [{{"min": [0, 0, 0], "max": [0.05, 0.05, 0.05]}}],
                      "spacing": 0.01{}}},
                    {{"name": "b", "kind": "continuum", "blocks": [{{"min": [0, 0.1, 0], "max": [0.05, 0.15, 0.05]}}],
                      "spacing": 0.01, "youngs_modulus": 1e5}}]}})",
                       solver, keys);
  };
  struct Case {
    std::string solver, keys;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {"xpbd", R"(, "youngs_modulus": 1e5)", {"settings.solver", "does not simulate continua", "'a'", "xpbi"}},
      {"nmd", R"(, "youngs_modulus": 1e5)", {"settings.solver", "does not simulate continua", "xpbi"}},
      {"xpbi", "", {"objects[0].youngs_modulus", "Young's modulus"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "poisson_ratio": 0.5)", {"objects[0].poisson_ratio", "out of range"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "plasticity": {"model": "cam_clay"})",
       {"objects[0].plasticity.model", "drucker_prager, von_mises, snow, herschel_bulkley, maxwell"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "plasticity": {"model": "drucker_prager", "friction_angle_deg": 95})",
       {"objects[0].plasticity.friction_angle_deg", "out of range"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "plasticity": {"model": "von_mises"})", {"yield_stress"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "plasticity": {"model": "herschel_bulkley", "shear_yield_stress": 50})",
       {"objects[0].plasticity", "consistency"}},
      {"xpbi",
       R"(, "youngs_modulus": 1e5, "plasticity": {"model": "herschel_bulkley", "shear_yield_stress": 50,
          "consistency": 1, "flow_index": 0})",
       {"objects[0].plasticity.flow_index", "out of range"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "plasticity": {"model": "maxwell"})", {"objects[0].plasticity", "relaxation_time"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "plasticity": {"model": "maxwell", "relaxation_time": 0})",
       {"objects[0].plasticity.relaxation_time", "out of range"}},
      {"xpbi", R"(, "youngs_modulus": 1e5, "spheres": [{"center": [0, 0.3, 0], "radius": 0.004}])",
       {"objects[0].spheres[0].radius", "at least one particle spacing (0.01 m) wide"}},
  };
  for (const Case& c : cases) {
    std::string message;
    try {
      load_scene_text(scene(c.solver, c.keys), "bad.json");
    } catch (const InputError& e) {
      message = e.what();
    }
    for (const std::string& part : c.expected) EXPECT_NE(message.find(part), std::string::npos) << c.keys << ": " << message;
  }
  // Two continua of unlike spacing: the second names the first's.
  std::string message;
  try {
    load_scene_text(fmt::format(R"({{"name": "bad", "settings": {{"solver": "xpbi"}},
        "objects": [{{"name": "a", "kind": "continuum", "blocks": [{{"min": [0, 0, 0], "max": [0.05, 0.05, 0.05]}}],
                      "spacing": 0.01, "youngs_modulus": 1e5}},
                    {{"name": "b", "kind": "continuum", "blocks": [{{"min": [0, 0.1, 0], "max": [0.05, 0.15, 0.05]}}],
                      "spacing": 0.005, "youngs_modulus": 1e5}}]}})"),
                    "bad.json");
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("objects[1].spacing"), std::string::npos) << message;
  EXPECT_NE(message.find("0.01 m"), std::string::npos) << message;
}

}  // namespace
}  // namespace moreau
