// Surface tension in N/m (src/moreau/fluids/surface_tension.hpp): a weightless drop's l = 2 shape
// oscillation against Rayleigh's omega^2 = l (l - 1) (l + 2) gamma / (rho0 R^3) = 8 gamma / (rho0 R^3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "damped_oscillation.hpp"
#include "drop_meshes.hpp"
#include "moreau/errors.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kDensity = 1000, kDropRadius = 0.01, kParticleRadius = 0.0005, kDt = 0.0005;

// A weightless inviscid drop of water (R = 1 cm, 4,224 particles at r = 0.5 mm) with surface tension gamma.
Scene drop_scene(Real gamma) {
  const std::string dir = test::temp_dir("capillary-drop");
  {
    std::ofstream out(dir + "/drop.obj");
    test::write_sphere_shell(out, 1, kDropRadius, Vec3::Zero());
  }
  return test::scene_from_json(fmt::format(R"({{"name": "drop", "settings": {{"dt": {}, "substeps": 2, "iterations": 2, "gravity": [0, 0, 0]}},
    "objects": [{{"name": "water", "kind": "fluid", "particle_radius": {}, "density": {}, "viscosity": 0, "xsph": 0,
      "surface_tension": {}, "mesh": "{}/drop.obj"}}]}})",
                                           kDt, kParticleRadius, kDensity, gamma, dir));
}

Vec3 centroid(const FluidState& f) {
  Vec3 sum = Vec3::Zero();
  for (Index i = 0; i < f.count; ++i) sum += f.position[i];
  return sum / static_cast<Real>(f.count);
}

// The drop's quadrupole moment <z^2> - (<x^2> + <y^2>) / 2 about its centroid, m^2: zero for a sphere,
// linear in the amplitude of the axisymmetric l = 2 mode.
Real quadrupole(const FluidState& f) {
  const Vec3 c = centroid(f);
  Real sum = 0;
  for (Index i = 0; i < f.count; ++i) {
    const Vec3 d = f.position[i] - c;
    sum += d.z() * d.z() - 0.5 * (d.x() * d.x() + d.y() * d.y());
  }
  return sum / static_cast<Real>(f.count);
}

// Brings the drop to rest (0.1 s with the velocities zeroed after each step: the filled lattice's
// corners settle), starts the l = 2 mode with the potential flow v = A (-x, -y, 2z) about the
// centroid, A = 0.05 omega_Rayleigh (the poles move out by 0.1 R, the equator in by 0.05 R), and
// fits 0.6 s of its quadrupole.
test::DampedOscillation oscillate(Real gamma) {
  Scene scene = drop_scene(gamma);
  FluidState& f = scene.state.fluid;
  EXPECT_EQ(f.count, 4224);
  for (int s = 0; s < 200; ++s) {
    test::run_steps(scene, 1);
    for (Index i = 0; i < f.count; ++i) f.velocity[i].setZero();
  }
  const Real rayleigh = std::sqrt(8 * gamma / (kDensity * std::pow(kDropRadius, 3)));
  const Real A = 0.05 * rayleigh;
  const Vec3 c = centroid(f);
  for (Index i = 0; i < f.count; ++i) {
    const Vec3 d = f.position[i] - c;
    f.velocity[i] = A * Vec3(-d.x(), -d.y(), 2 * d.z());
  }
  std::vector<Real> t, q;
  for (int s = 1; s <= 1200; ++s) {
    test::run_steps(scene, 1);
    t.push_back(s * kDt);
    q.push_back(quadrupole(f));
  }
  Real escaped = 0;
  const Vec3 end = centroid(f);
  for (Index i = 0; i < f.count; ++i) escaped += (f.position[i] - end).norm() > 1.25 * kDropRadius;
  EXPECT_EQ(escaped, 0) << "particles left the drop";
  return test::fit_damped_oscillation(t, q);
}

TEST(FluidSurfaceTension, ADropOscillatesAtRayleighsFrequency) {
  // Rayleigh (1879): omega_2^2 = 8 gamma / (rho0 R^3) for an inviscid drop; for water (0.072 N/m,
  // R = 1 cm) 24.0 rad/s. The fit's omega_0 = sqrt(omega_d^2 + alpha^2) is the natural frequency
  // under the numerical damping alpha. Tolerance 5 % (the validation target). Measured: -1.5 %
  // (water) and +0.4 % (0.15 N/m); damping ratios 0.06.
  for (Real gamma : {0.072, 0.15}) {
    const test::DampedOscillation fit = oscillate(gamma);
    const Real rayleigh = std::sqrt(8 * gamma / (kDensity * std::pow(kDropRadius, 3)));
    std::printf("gamma %.3f N/m: omega_0 %.2f rad/s against Rayleigh's %.2f (%+.2f %%); damping ratio %.3f\n", gamma,
                fit.natural(), rayleigh, 100 * (fit.natural() / rayleigh - 1), fit.decay / fit.natural());
    EXPECT_NEAR(fit.natural() / rayleigh, 1, 0.05) << "gamma " << gamma;
    EXPECT_LT(fit.decay / fit.natural(), 0.2) << "the oscillation is damped much more than measured (0.06)";
  }
}

TEST(FluidSurfaceTension, TheStepMustResolveCapillaryWaves) {
  // dt <= sqrt(rho0 (2r)^3 / (2 pi gamma)) = 1.49 ms for water at r = 0.5 mm: 2 ms is refused (exit 2 at
  // the command line) with the key and the limit named.
  try {
    test::scene_from_json(R"({"name": "drop", "settings": {"dt": 0.002, "gravity": [0, 0, 0]},
      "objects": [{"name": "water", "kind": "fluid", "particle_radius": 0.0005, "surface_tension": 0.072,
        "block": {"min": [0, 0, 0], "max": [0.01, 0.01, 0.01]}}]})");
    FAIL() << "a step longer than the capillary limit was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("objects[0].surface_tension"), std::string::npos) << message;
    EXPECT_NE(message.find("0.00149"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace moreau
