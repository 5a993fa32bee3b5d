// The no-slip extrapolation through a turning rigid body (fluid_viscosity.cpp): liquid that turns
// rigidly with a turning sphere with `fluid_friction` 1 has no strain, so the implicit viscosity
// must leave its rigid rotation as it is. The sample's velocity is extrapolated with the body's
// velocity where the line from the particle to the sample crosses the surface; with the body's
// velocity at the sample's own surface point instead, liquid next to the turning body would feel
// a shear of beta times the body's turning across the line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "drop_meshes.hpp"
#include "moreau/fluids/fluid_neighbors.hpp"
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_viscosity.hpp"
#include "moreau/fluids/solid_coupling.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kSphere = 0.01;           // R, m
constexpr Real kParticleRadius = 0.001;  // r_p
constexpr Real kSpin = 2;                // Omega, rad/s, about z

TEST(FluidRigidFriction, LiquidTurningWithATurningSphereFeelsNoShearFromIt) {
  // A 4 cm block of mu = 10 Pa s liquid around the sphere (the lattice points outside R + r_p),
  // turning with it, u = Omega x x, and one implicit viscosity solve over a substep (1/1200 s) on
  // its own: no density solve moves the particles. The liquid has no strain, so the solve must
  // leave its velocities alone, next to the sphere too, where its samples enter the sums.
  const std::string dir = test::temp_dir("co-rotating-sphere");
  const Vec3 center(0, 0.02, 0), omega(0, 0, kSpin);
  test::write_drop_meshes(dir, 0.02, 0.04, kSphere + kParticleRadius, center);
  Scene scene = test::scene_from_json(fmt::format(
      R"({{"name": "co-rotating", "settings": {{"dt": 0.008333333333333333, "substeps": 10, "gravity": [0, 0, 0]}},
    "objects": [
      {{"name": "ball", "kind": "rigid_body", "kinematic": true, "fluid_friction": 1, "angular_velocity": [0, 0, {}],
        "shape": {{"type": "sphere", "radius": {}}}, "position": [0, 0.02, 0]}},
      {{"name": "liquid", "kind": "fluid", "particle_radius": {}, "viscosity": 10, "xsph": 0, "mesh": "{}/surround.obj"}}]}})",
      kSpin, kSphere, kParticleRadius, dir));
  FluidState& f = scene.state.fluid;
  FluidScratch scratch;
  scratch.fit(scene.model.fluid);
#pragma omp parallel num_threads(1)
  {
    place_solid_samples(scene.model, scene.state);
    update_fluid_neighbors(scene.model, f, scratch, 0);
  }
  for (Index i = 0; i < f.count; ++i) f.velocity[i] = omega.cross(f.position[i] - center);
#pragma omp parallel num_threads(1)
  apply_implicit_fluid_viscosity(scene.model, scene.state, scratch, 1.0 / 1200);
  // Bound: 1e-4 of Omega R, the solve's relative residual. Measured: 2e-16 (the right-hand side
  // vanishes). With the body's velocity taken at each sample's own surface point instead, the wall
  // terms dragged the particles next to the sphere off rigid rotation by 2.9e-2 of Omega R in this
  // one substep (2.9e-3 elsewhere).
  Real worst = 0, worst_far = 0;
  Index near = 0;
  for (Index i = 0; i < f.count; ++i) {
    const Vec3 x = f.position[i] - center;
    ASSERT_TRUE(f.velocity[i].allFinite());
    const Real departure = (f.velocity[i] - omega.cross(x)).norm() / (kSpin * kSphere);
    if (x.norm() <= kSphere + 4 * kParticleRadius) ++near, worst = std::max(worst, departure);
    else worst_far = std::max(worst_far, departure);
  }
  std::printf("%d particles within h of the sphere: largest departure from rigid rotation %.2e of Omega R "
              "(elsewhere %.2e)\n", static_cast<int>(near), worst, worst_far);
  ASSERT_GT(near, 500);
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
}  // namespace moreau
