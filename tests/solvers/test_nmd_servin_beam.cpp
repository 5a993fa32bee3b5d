// The Servin et al. (2006) elastic solid under "nmd" against the FEM engine's cantilever: a
// St. Venant-Kirchhoff beam whose tetrahedra carry their Green strain in Voigt form as six rows of
// compliance (V D)^-1. Its energy is the FEM's St. Venant-Kirchhoff energy on linear tetrahedra, and
// the lumped weight rho g V / 4 per vertex is the consistent body load of a linear tetrahedron, so
// on the same mesh the velocity-level solve must settle where the FEM static solve lands.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

// A 0.5 x 0.1 x 0.1 m beam along x, clamped at x = 0, sagging under its weight (rho = 1000,
// nu = 0.3). Euler-Bernoulli gives q L^4 / (8 E I) = 0.92 mm at E = 1e8 Pa, a bending strain of at
// most 7e-4 at the clamp, so the St. Venant-Kirchhoff response is linear to about that fraction.
constexpr Real kLength = 0.5;
constexpr const char* kMaterial = R"("material": {{"model": "st_venant_kirchhoff", "youngs_modulus": {}, "poisson_ratio": 0.3, "density": 1000}})";
constexpr const char* kTipProbe = R"("probes": [{"name": "tip", "type": "point", "object": "beam", "nearest": [0.5, 0.05, 0.05], "quantity": "displacement"}])";

using Cells = std::array<int, 3>;

// The tip's vertical displacement at the FEM engine's static equilibrium (one load step).
Real fem_tip(const Cells& c, const char* element, Real youngs) {
  World w = World::from_json(fmt::format(
      R"({{"name": "fem_beam", "settings": {{"solver": "fem", "dt": 1, "duration": 1, "integrator": "static"}},
      "objects": [{{"name": "beam", "kind": "solid", "mesh": {{"type": "box", "min": [0, 0, 0], "max": [0.5, 0.1, 0.1], "cells": [{}, {}, {}], "element": "{}"}},
        {}, "dirichlet": [{{"where": {{"boundary": "left"}}, "value": [0, 0, 0]}}]}}], {}}})",
      c[0], c[1], c[2], element, fmt::format(kMaterial, youngs), kTipProbe));
  w.step();
  return w.probe_values()[1];
}

// The tip under "nmd" (direct) after `steps` steps of 1 s, the largest |tip| on the way. A step far
// longer than the beam's period (0.05 s at E = 1e8) makes the inertia M / h^2 negligible beside
// the stiffness: each step is a linearised solve of the static balance relaxed by SPOOK, and the
// steps settle on it (the tip is within 1e-9 of its final value after 20).
struct NmdTip {
  Real last = 0, largest = 0;
};
NmdTip nmd_tip(const Cells& c, Real youngs, int steps) {
  World w = World::from_json(fmt::format(
      R"({{"name": "nmd_beam", "settings": {{"solver": "nmd", "dt": 1, "duration": {}, "nmd": {{"method": "direct"}}}},
      "objects": [{{"name": "beam", "kind": "soft_body", "mesh": {{"type": "box", "min": [0, 0, 0], "max": [0.5, 0.1, 0.1], "cells": [{}, {}, {}]}},
        {}, "pin": [{{"box": {{"min": [-0.001, -1, -1], "max": [0.001, 1, 1]}}}}]}}], {}}})",
      steps, c[0], c[1], c[2], fmt::format(kMaterial, youngs), kTipProbe));
  NmdTip tip;
  for (int s = 0; s < steps; ++s) {
    w.step();
    tip.last = w.probe_values()[1];
    tip.largest = std::max(tip.largest, std::abs(tip.last));
  }
  return tip;
}

TEST(NmdServinBeam, SettlesOnTheFemCantileverOfTheSameMeshAndConvergesWithIt) {
  const Real youngs = 1e8;
  // The continuum reference: the FEM engine's trilinear hexahedra, 40 x 8 x 8 cells.
  const Real reference = fem_tip({40, 8, 8}, "hex8", youngs);
  Real last_error = 1;
  for (const Cells& cells : {Cells{10, 2, 2}, Cells{20, 4, 4}}) {
    const Real fem = fem_tip(cells, "tet4", youngs);
    const NmdTip nmd = nmd_tip(cells, youngs, 25);
    const Real error = std::abs(nmd.last / reference - 1);
    fmt::print("Servin beam {}x{}x{} cells (6 tets each): nmd {:.6e} m, FEM tet4 {:.6e} m ({:+.1e}); {:.1f} % from FEM hex8 40x8x8 {:.6e} m\n",
               cells[0], cells[1], cells[2], nmd.last, fem, nmd.last / fem - 1, 100 * error, reference);
    // The same discrete problem: equal to the static solve's tolerance (1e-10) and the steps' settling.
    EXPECT_NEAR(nmd.last, fem, 1e-6 * std::abs(fem));
    // Linear tetrahedra are stiff in bending; refinement must close the gap.
    EXPECT_LT(error, last_error);
    last_error = error;
  }
  // The sequence's next mesh, by the FEM engine on the same tetrahedra (the velocity-level solve of
  // its 92,160 rows takes minutes a step): linear tetrahedra still lock by 5 % at 8 through the height.
  const Real fine = fem_tip({40, 8, 8}, "tet4", youngs);
  fmt::print("FEM tet4 40x8x8: {:.6e} m, {:.1f} % from hex8\n", fine, 100 * std::abs(fine / reference - 1));
  EXPECT_LT(std::abs(fine / reference - 1), last_error);
}

TEST(NmdServinBeam, StaysStableAsTheComplianceGoesToZero) {
  // The deflection of a linear beam scales as 1/E. Raising E by 1e3 at a time to 1e17 Pa (eps =
  // (V D)^-1 down to 5e-13 1/(N m)), SPOOK's regularised solve stays bounded and settles: the tip
  // follows 1/E until round-off sets a floor of about 1e-11 m (a 2e-11 strain). The first step
  // cancels a free fall of g h^2 = 9.8 m against the rows to about 1e-9 of it, whatever E; SPOOK
  // then relaxes that error away within a few steps (d = 2).
  const Cells cells{10, 2, 2};
  const Real base = nmd_tip(cells, 1e8, 25).last * 1e8;  // E delta at the linear limit
  EXPECT_NEAR(base, fem_tip(cells, "tet4", 1e8) * 1e8, 1e-6 * std::abs(base));
  const Real free_fall = 9.81 * 1 * 1;
  for (const Real youngs : {1e11, 1e14, 1e17}) {
    const NmdTip tip = nmd_tip(cells, youngs, 25);
    fmt::print("E = {:.0e} Pa: tip {:.3e} m (1/E law {:.3e} m, {:+.1e} relative), largest on the way {:.3e} m\n",
               youngs, tip.last, base / youngs, tip.last * youngs / base - 1, tip.largest);
    EXPECT_LE(tip.largest, 2 * std::abs(base) / youngs + 1e-8 * free_fall);
    EXPECT_LE(std::abs(tip.last), 2 * std::abs(base) / youngs + 1e-10);
    if (youngs <= 1e11) {
      EXPECT_NEAR(tip.last * youngs, base, 1e-3 * std::abs(base));
    }
  }
}

}  // namespace
}  // namespace moreau
