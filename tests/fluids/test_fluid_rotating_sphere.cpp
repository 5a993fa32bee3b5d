// A rigid sphere turning steadily in a viscous liquid that fills a fixed spherical shell around it
// (`fluid_friction` 1 on both): the liquid's azimuthal velocity against the Stokes flow between
// concentric spheres. It checks the no-slip extrapolation through a turning, curved rigid surface
// (fluid_viscosity.cpp), where the wall's velocity varies from sample to sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "drop_meshes.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kSphere = 0.01, kShell = 0.025;  // m: R and R_c
constexpr Real kParticleRadius = 0.001;         // r_p: R / (2 r_p) = 5 spacings per sphere radius
constexpr Real kSpin = 2;                       // Omega, rad/s

// Stokes flow between a sphere of radius R turning at Omega about z and a fixed concentric sphere of
// radius R_c (u = (a r + b / r^2) sin(theta) e_phi, no slip on both):
//   u_phi = Omega R^3 (R_c^3 / r^2 - r) / (R_c^3 - R^3) sin(theta).
// Here Re = Omega R^2 / nu = 0.02, so inertia is negligible.
Real stokes_speed_over_sin(Real r) {
  const Real R3 = std::pow(kSphere, 3), Rc3 = std::pow(kShell, 3);
  return kSpin * R3 * (Rc3 / (r * r) - r) / (Rc3 - R3);
}

TEST(FluidRigidFriction, ATurningSphereDrivesStokesFlowInASphericalShell) {
  // The liquid fills the lattice points between spheres of R + r_p and R_c - r_p: each particle
  // stands for a cube of side 2 r_p, so the liquid's volume is the shell's.
  const std::string dir = test::temp_dir("turning-sphere");
  {
    std::ofstream liquid(dir + "/liquid.obj");
    test::write_sphere_shell(liquid, 1, kShell - kParticleRadius, Vec3::Zero());
    test::write_sphere_shell(liquid, 1 + 258, kSphere + kParticleRadius, Vec3::Zero());
  }
  // mu = 10 Pa s (nu = 0.01 m^2/s): the flow settles in a few (R_c - R)^2 / nu = 0.023 s; 0.15 s.
  Scene scene = test::scene_from_json(fmt::format(
      R"({{"name": "turning", "settings": {{"dt": 0.008333333333333333, "substeps": 10, "gravity": [0, 0, 0]}},
    "objects": [
      {{"name": "shell", "kind": "collider", "inside": true, "fluid_friction": 1,
        "shape": {{"type": "sphere", "center": [0, 0, 0], "radius": {}}}}},
      {{"name": "ball", "kind": "rigid_body", "kinematic": true, "fluid_friction": 1, "angular_velocity": [0, 0, {}],
        "shape": {{"type": "sphere", "radius": {}}}, "position": [0, 0, 0]}},
      {{"name": "liquid", "kind": "fluid", "particle_radius": {}, "viscosity": 10, "xsph": 0, "mesh": "{}/liquid.obj"}}]}})",
      kShell, kSpin, kSphere, kParticleRadius, dir));
  test::run_steps(scene, 18);
  // Each particle's u_phi / sin(theta) against the exact, averaged in seven equal radial bins from R
  // to R_c - 2 r_p, over the particles within 60 degrees of the equator (sin(theta) >= 0.5).
  const FluidState& f = scene.state.fluid;
  constexpr int kBins = 7;
  const Real width = (kShell - kSphere - 2 * kParticleRadius) / kBins;
  std::vector<Real> sum(kBins, 0), exact(kBins, 0);
  std::vector<int> count(kBins, 0);
  for (Index i = 0; i < f.count; ++i) {
    const Vec3 x = f.position[i];
    const Real r = x.norm(), rho = std::hypot(x.x(), x.y());
    if (rho < 0.5 * r) continue;
    const int bin = static_cast<int>(std::floor((r - kSphere) / width));
    if (bin < 0 || bin >= kBins) continue;
    const Vec3 phi(-x.y() / rho, x.x() / rho, 0);
    sum[bin] += f.velocity[i].dot(phi) / (rho / r);
    exact[bin] += stokes_speed_over_sin(r);
    ++count[bin];
  }
  // Measured: +5.1 % of Omega R in the bin next to the sphere, +7.9 % at most (2-6 mm out), within
  // 1 % beyond 7 mm. At r_p = 0.5 mm, in 1 mm bins, the same shape (+9.5 % at most): the liquid
  // near the sphere turns a little too fast, by an error that does not shrink with the spacing and
  // is linear in Omega (the same figures at 0.5 rad/s), so it is not inertia.
  // Sampling the sphere from a 48 x 96 instead of its 12 x 24 latitude-longitude mesh (facets
  // closer to the true surface) made it worse, +10.0 %: the no-slip surface of a convex body seems
  // to sit a little outside it. The bound, 10 % of Omega R, is empirical: the measured 7.9 % with
  // a margin. (Taking the wall's velocity at each sample's own surface point, instead of where the
  // line from the particle to the sample crosses the surface, gave +10.9 %.)
  Real worst = 0;
  for (int b = 0; b < kBins; ++b) {
    ASSERT_GT(count[b], 0);
    const Real measured = sum[b] / count[b], expected = exact[b] / count[b];
    ASSERT_TRUE(std::isfinite(measured)) << "bin " << b;
    std::printf("r %.1f-%.1f mm: u_phi / sin(theta) %.5f, Stokes %.5f m/s (%+.2f %% of Omega R)\n",
                1e3 * (kSphere + width * b), 1e3 * (kSphere + width * (b + 1)), measured, expected,
                100 * (measured - expected) / (kSpin * kSphere));
    worst = std::max(worst, std::abs(measured - expected) / (kSpin * kSphere));
  }
  EXPECT_LT(worst, 0.10);
}

}  // namespace
}  // namespace moreau
