// Constraint fluids under "nmd" (Bodin, Lacoursiere, Servin 2012): the fluid as one density row per
// particle in the velocity-level system, walls and solid samples as unilateral rows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "moreau/model/diagnostics.hpp"
#include "fluid_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

// 0.2 m of water at rest in a tank with a 0.15 m square base, r = 6.25 mm: 12 x 16 x 12 = 2,304
// particles, 16 layers (the position-level tank of tests/fluids/test_fluids.cpp), one velocity
// solve of 50 Gauss-Seidel sweeps per 4 ms step.
const char* kTank = R"({"name": "tank", "settings": {"solver": "nmd", "dt": 0.004, "nmd": {"iterations": 50}},
  "objects": [
    {"name": "tank", "kind": "collider", "inside": true,
     "shape": {"type": "box", "center": [0, 0.25, 0], "half_extents": [0.075, 0.25, 0.075]}},
    {"name": "water", "kind": "fluid", "particle_radius": 0.00625,
     "block": {"min": [-0.075, 0, -0.075], "max": [0.075, 0.2, 0.075]}}]})";

TEST(NmdConstraintFluid, TankAtRestHasTheHydrostaticPressure) {
  Scene scene = scene_from_json(kTank);
  const FluidState& f = scene.state.fluid;
  const Real r = 0.00625, d = 2 * r;
  run_steps(scene, 250);  // 1 s
  // The pressure -lambda / V of each particle's row, averaged per 2r-thick layer over 0.5 s, and
  // fitted by least squares, as for the position-level tank: the inner columns (more than h = 4r
  // from the side walls), the layers more than h from the floor and below the surface layers.
  const int layers = 12;
  std::vector<Real> layer_sum(layers, 0.0), layer_y(layers, 0.0);
  std::vector<long> layer_count(layers, 0);
  for (int sample = 0; sample < 125; ++sample) {
    run_steps(scene, 1);
    for (Index i = 0; i < f.count; ++i) {
      const Vec3& x = f.position[i];
      const int k = static_cast<int>(std::floor((x.y() - 4 * r) / d));
      if (std::abs(x.x()) > 0.075 - 4 * r || std::abs(x.z()) > 0.075 - 4 * r || k < 0 || k >= layers) continue;
      layer_sum[k] += f.pressure[i], layer_y[k] += x.y(), ++layer_count[k];
    }
  }
  Real sy = 0, sp = 0, syy = 0, syp = 0, spp = 0;
  for (int k = 0; k < layers; ++k) {
    const Real y = layer_y[k] / layer_count[k], p = layer_sum[k] / layer_count[k];
    std::printf("layer y = %.4f m: p = %.1f Pa (hydrostatic %.1f)\n", y, p, 9810 * (0.2 - y));
    sy += y, sp += p, syy += y * y, syp += y * p, spp += p * p;
  }
  const Real cov = layers * syp - sy * sp, var_y = layers * syy - sy * sy, var_p = layers * spp - sp * sp;
  const Real slope = cov / var_y, r2 = cov * cov / (var_y * var_p);
  const Real surface = (sp - slope * sy) / layers / -slope;
  Real mean_error = 0;
  for (Index i = 0; i < f.count; ++i) mean_error += std::max(f.density[i] / 1000 - 1, 0.0);
  mean_error /= f.count;
  // What the rows do: each interior particle's weight is carried by the pressure rows of itself and
  // its neighbours, F_i = sum_j lambda_j grad_{x_i} C_j = -V^2 sum_j (p_i + p_j) grad W_ij (the
  // symmetric SPH pressure force; lambda = -p V). Its mean over the fitted region equals m g up to
  // what the fluid still accelerates (a settled tank: well under 1 %).
  const CubicSplineKernel& kernel = scene.model.fluid.kernel;
  const Real V = scene.model.fluid.particle_volume, weight = 1000 * V * 9.81;
  Real force = 0;
  long counted = 0;
  for (Index i = 0; i < f.count; ++i) {
    const Vec3& x = f.position[i];
    if (std::abs(x.x()) > 0.075 - 4 * r || std::abs(x.z()) > 0.075 - 4 * r || x.y() < 4 * r || x.y() > 0.2 - 4 * r)
      continue;
    for (Index j = 0; j < f.count; ++j) {
      const Vec3 rij = x - f.position[j];
      const Real distance = rij.norm();
      if (j != i && distance < kernel.h) force -= V * V * (f.pressure[i] + f.pressure[j]) * kernel.gradient_factor(distance) * rij.y();
    }
    ++counted;
  }
  force /= counted;
  std::printf("pressure gradient %.1f Pa/m (rho g = 9810), R^2 = %.5f, p = 0 at y = %.4f m, mean compression %.2e; "
              "mean row force %.5e N on a particle of weight %.5e N\n", -slope, r2, surface, mean_error, force, weight);
  EXPECT_NEAR(force, weight, 0.01 * weight);
  // The layers' mean pressure is linear in depth, its slope rho g up to the SPH gradient's
  // discretisation error on the settled arrangement: with the per-particle pressures the rows
  // balance the weight (above), with the fitted linear profile they would push 3 % too hard, so the
  // slope is 3-4 % steeper than rho g (the position-level tank: 1-4 %). Bound 6 %, as there.
  EXPECT_NEAR(-slope, 9810, 0.06 * 9810);
  EXPECT_GT(r2, 0.995);
  EXPECT_NEAR(surface, 0.2, 0.02 * 0.2);
  EXPECT_LT(mean_error, 0.001);
}

}  // namespace
}  // namespace moreau
