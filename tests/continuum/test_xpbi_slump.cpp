// The slump test of a yield-stress fluid (a Bingham paste under XPBI) against the published
// slump relation: a column stops where the weight above each level no longer exceeds the yield
// stress, at a height that rises with the yield stress.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "moreau/model/diagnostics.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {
namespace {

constexpr Real kHeight = 0.1, kDensity = 1000, kGravity = 9.81;

// The slump relation of Murata (1984) and Pashias, Boger, Summers, Glenister (1996, "A fifty cent
// rheometer for yield stress measurement", J. Rheol. 40): a column of height H released on a
// plate yields where the weight of what lies above a level, spread over that level's area,
// exceeds the uniaxial yield stress sigma_Y. The top s H, s = sigma_Y / (rho g H), stays rigid;
// below it a layer at depth z is squeezed until its area carries rho g z over the original area
// at sigma_Y, thinning by the factor s H / z, which integrates to a final height
//   h / H = s (1 - ln s)   (s < 1).
// Pashias et al. write sigma_Y = 2 tau_y (Tresca); the von Mises form of our yield surface has
// sigma_Y = sqrt(3) tau_y, as Roussel and Coussot (2005, J. Rheol. 49) use it.
Real slump_relation_height(Real shear_yield_stress) {
  const Real s = std::sqrt(Real(3)) * shear_yield_stress / (kDensity * kGravity * kHeight);
  return kHeight * s * (1 - std::log(s));
}

struct Slump {
  Real height, kinetic, mass;
};

// A cylinder 0.1 m tall and 0.07 m wide of Bingham paste (consistency 10 Pa s), 20 particles
// tall, on a plate with friction (as the slump test's plate holds the paste's foot), after 0.8 s.
// E = 30 kPa keeps the elastic strain at yield below 1.7 % (its share of the height is below 1 %)
// while allowing 10 substeps of 0.5 ms.
Slump slump(Real shear_yield_stress) {
  Scene scene = load_scene_text(
      fmt::format(R"({{"name": "slump", "settings": {{"solver": "xpbi", "dt": 0.005, "substeps": 10, "iterations": 3}},
      "objects": [{{"name": "plate", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.5}},
                  {{"name": "paste", "kind": "continuum", "cylinders": [{{"base": [0, 0, 0], "radius": 0.035, "height": {}}}],
                    "spacing": 0.005, "density": {}, "youngs_modulus": 3e4, "poisson_ratio": 0.3, "friction": 0.5,
                    "plasticity": {{"model": "herschel_bulkley", "shear_yield_stress": {}, "consistency": 10}}}}]}})",
                  kHeight, kDensity, shear_yield_stress),
      "slump");
  StageTimer timer;
  for (int k = 0; k < 160; ++k) scene.formulation->step(scene.model, scene.state, timer, 1);
  Real top = 0;
  for (const Vec3& x : scene.state.position) top = std::max(top, x.y());
  // The top particle's centre lies half a spacing below the surface.
  Real mass = 0;
  for (Index p : scene.model.continuum.particle) mass += scene.model.particle_mass[p];
  return {top + scene.model.continuum.spacing / 2, kinetic_energy(scene.model, scene.state, 1), mass};
}

// Three yield stresses, s = 0.2, 0.35 and 0.5 (slumps of 48 %, 28 % and 15 %). The relation is a
// one-dimensional model (it leaves out the shear in the slumped foot); 10 % is the issue's bound.
// At 20 particles across the height the runs land within 4.6 % (10 particles: 15 %).
TEST(XpbiSlump, AYieldStressPasteStopsAtTheSlumpRelationsHeight) {
  Real previous = 0;
  for (const Real s : {0.2, 0.35, 0.5}) {
    const Real shear_yield_stress = s * kDensity * kGravity * kHeight / std::sqrt(Real(3));
    const Slump result = slump(shear_yield_stress);
    const Real expected = slump_relation_height(shear_yield_stress);
    fmt::print("tau_y {:.1f} Pa (s = {}): height {:.4f} m against {:.4f} m ({:+.2f} %), kinetic {:.2g} J\n",
               shear_yield_stress, s, result.height, expected, 100 * (result.height / expected - 1), result.kinetic);
    EXPECT_NEAR(result.height / expected, 1, 0.10);
    EXPECT_GT(result.height, previous + 0.01) << "a higher yield stress must stand taller";
    previous = result.height;
    // At rest: what still moves is elastic ringing, below 1e-3 of the potential energy the slump
    // released, m g (H - h) / 2 with the centre of mass near half the height.
    EXPECT_LT(result.kinetic, 1e-3 * result.mass * kGravity * (kHeight - result.height) / 2);
  }
}

}  // namespace
}  // namespace moreau
