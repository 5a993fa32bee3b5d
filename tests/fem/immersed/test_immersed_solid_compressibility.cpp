// An immersed solid keeps its own Poisson's ratio. The fluid's continuity equation holds over the
// solid too, which would make the solid's motion incompressible, but it does not for a solid with
// cells the fluid's size or larger, here with its nodes on the fluid's: such a solid changes
// volume as it does alone (why is not established; in a build with PSPG's tau scaled by 1e-3 the
// result below moved by less than 1e-8 of it, which a leak at a rate set by tau would not change
// either: it would change how fast the bar comes to rest; docs/validation.md). Checked through the
// command line: a cantilever at rest in a closed box of fluid, heavier than the fluid, settles where
// the same cantilever alone settles under the same net load, not where an incompressible one would.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "scene_test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

// A St. Venant-Kirchhoff cantilever 0.2 x 0.02 m (shear modulus 0.5 MPa, nu = 0.4, as Turek &
// Hron's bar), clamped on its left end, under a net load of 20 N/m^3 downward.
constexpr const char* kBar = R"({{"name": "bar", "kind": "solid",
    "mesh": {{"type": "rectangle", "min": [0.02, 0.04], "max": [0.22, 0.06], "cells": [{}, {}]}},
    "material": {{"model": "{}", "lame_lambda": {}, "lame_mu": 5e5, "density": {}}},{}
    "dirichlet": [{{"where": {{"boundary": "left"}}, "value": [0, 0]}}]}})";
constexpr const char* kTip = R"([{"name": "tip", "type": "point", "object": "bar", "nearest": [0.22, 0.05], "quantity": "displacement"}])";

// The bar of `along` x `across` cells (40 x 4: the fluid's 5 mm cells below).
std::string bar(const char* model, Real lambda, Real density, const char* extra = "", int along = 40, int across = 4) {
  return fmt::format(fmt::runtime(kBar), along, across, model, lambda, density, extra);
}

// The tip's vertical displacement of the last row of a run (m).
Real final_tip_y(const std::string& name, const std::string& scene) {
  const std::string path = test::write_scene(name, scene);
  const auto rows = test::run_scene(path, (fs::path(path).parent_path() / "out").string(), "--threads 1");
  return rows.empty() ? NAN : rows.back()[2];
}

TEST(ImmersedSolid, AStressedSolidKeepsItsOwnPoissonsRatio) {
  // The bar alone, static, 2 kg/m^3 under g = 10: 20 N/m^3, with nu = 0.4 and nearly
  // incompressible (nu = 0.4999, mean dilatation, the same shear modulus).
  const std::string alone = R"({"name": "alone", "settings": {"solver": "fem", "integrator": "static", "dt": 1, "duration": 1,
      "gravity": [0, -10, 0], "newton": {"tolerance": 1e-10}}, "objects": [)";
  const Real compressible = final_tip_y("bar-alone", alone + bar("st_venant_kirchhoff", 2e6, 2) + "], \"probes\": " + kTip + "}");
  const Real incompressible_lambda = 2 * 5e5 * 0.4999 / (1 - 2 * 0.4999);
  const Real incompressible = final_tip_y("bar-incompressible", alone +
                                          bar("neo_hookean", incompressible_lambda, 2, R"( "formulation": "mean_dilatation",)") +
                                          "], \"probes\": " + kTip + "}");
  // Immersed, 1002 kg/m^3 in 1000 kg/m^3 of a 1 Pa s fluid filling a closed 0.3 x 0.1 m box of
  // 60 x 20 cells (the bar four cells thick), ten backward Euler steps of 1 s to rest (with steps
  // of 0.1 s the bar swings about its resting place for many steps; the resting state does not
  // depend on the step).
  const std::string immersed = R"({"name": "immersed", "settings": {"solver": "fem", "integrator": "backward_euler", "dt": 1,
      "duration": 10, "gravity": [0, -10, 0], "newton": {"tolerance": 1e-10, "max_iterations": 40}, "output": {"every": 10, "formats": []}},
    "objects": [{"name": "fluid", "kind": "fluid", "mesh": {"type": "rectangle", "min": [0, 0], "max": [0.3, 0.1], "cells": [60, 20]},
                 "density": 1000, "viscosity": 1.0, "boundaries": [{"where": {"side": ["left", "right", "top", "bottom"]}, "type": "no_slip"}],
                 "pressure_reference": {"point": [0.29, 0.05], "value": 0}}, )";
  const Real in_fluid = final_tip_y("bar-immersed", immersed + bar("st_venant_kirchhoff", 2e6, 1002) + "], \"probes\": " + kTip + "}");
  std::printf("tip deflection: immersed %.6e m, alone %.6e m (nu = 0.4), %.6e m (incompressible)\n", in_fluid, compressible,
              incompressible);
  // Measured: the immersed tip within 3e-8 (relative) of the bar alone; the incompressible bar bends 10.5 %
  // less. On Turek & Hron's channel and bar meshes the difference was up to 0.3 %; 0.5 % keeps it
  // far from the incompressible answer.
  EXPECT_NEAR(in_fluid / compressible, 1, 0.005);
  EXPECT_LT(incompressible / compressible, 0.92);

  // A bar of 20 x 2 cells (10 mm, its nodes on every other fluid node), coarser than the fluid: it
  // too settles where it does alone (measured within 2e-10; with its coarser cells it bends 16 %
  // less than the 40 x 4 bar). 0.5 % as above: the same bar incompressible (nu = 0.4999, mean
  // dilatation) settles 11 % away, at -62.01 um (on two cells across, the mean-dilatation bar
  // locks less than St. Venant-Kirchhoff's).
  const Real coarse_alone = final_tip_y("coarse-bar-alone", alone + bar("st_venant_kirchhoff", 2e6, 2, "", 20, 2) +
                                                                "], \"probes\": " + kTip + "}");
  const Real coarse_in_fluid = final_tip_y("coarse-bar-immersed", immersed + bar("st_venant_kirchhoff", 2e6, 1002, "", 20, 2) +
                                                                      "], \"probes\": " + kTip + "}");
  std::printf("20 x 2 bar: immersed %.6e m, alone %.6e m\n", coarse_in_fluid, coarse_alone);
  EXPECT_NEAR(coarse_in_fluid / coarse_alone, 1, 0.005);
}

}  // namespace
}  // namespace moreau
