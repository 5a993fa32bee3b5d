// Interfacial tension between two liquids (src/moreau/fluids/interfacial_tension.hpp): a 1 cm drop
// of one liquid inside another of the same density, filling a spherical tank of 1.7 cm radius.
// Weightless, the drop's l = 2 oscillation against Lamb's frequency for a drop in a rigid spherical
// container. Under gravity, which gives the surrounding liquid the pressure the drop pushes against,
// the Young-Laplace jump of the resting drop's pressure. (Under gravity the oscillation dies within
// a tenth of a second even without tension: two density iterations a substep leave the 3.4 cm
// column settling, and each projection takes kinetic energy out of the flow.)
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

constexpr Real kDensity = 1000, kDrop = 0.01, kTank = 0.017, kParticleRadius = 0.0005, kDt = 0.0005, kGravity = 9.81;

// The tank (a sphere collider, "inside") filled with the liquid "outer" around the drop "inner",
// both water-dense and inviscid, whose interface has the tension sigma, under the gravity g (m/s^2).
// The two OBJ surfaces share one lattice: the spheres' bounding boxes are a whole number of
// spacings apart.
Scene drop_in_liquid(Real sigma, Real gravity) {
  const std::string dir = test::temp_dir("drop-in-liquid");
  {
    std::ofstream drop(dir + "/drop.obj");
    test::write_sphere_shell(drop, 1, kDrop, Vec3::Zero());
    std::ofstream outer(dir + "/outer.obj");
    test::write_sphere_shell(outer, 1, kTank, Vec3::Zero());
    test::write_sphere_shell(outer, 1027, kDrop, Vec3::Zero());
  }
  return test::scene_from_json(fmt::format(
      R"({{"name": "drop-in-liquid", "settings": {{"dt": {}, "substeps": 2, "iterations": 2, "gravity": [0, -{}, 0]}},
    "objects": [
      {{"name": "tank", "kind": "collider", "inside": true, "shape": {{"type": "sphere", "center": [0, 0, 0], "radius": {}}}}},
      {{"name": "outer", "kind": "fluid", "particle_radius": {}, "density": {}, "viscosity": 0, "xsph": 0, "mesh": "{}/outer.obj"}},
      {{"name": "inner", "kind": "fluid", "particle_radius": {}, "density": {}, "viscosity": 0, "xsph": 0, "mesh": "{}/drop.obj",
        "interfacial_tension": {{"outer": {}}}}}]}})",
      kDt, gravity, kTank, kParticleRadius, kDensity, dir, kParticleRadius, kDensity, dir, sigma));
}

bool in_drop(const Scene& scene, Index i) { return scene.state.fluid.phase[i] == 1; }

Vec3 drop_centroid(const Scene& scene) {
  const FluidState& f = scene.state.fluid;
  Vec3 sum = Vec3::Zero();
  Index count = 0;
  for (Index i = 0; i < f.count; ++i)
    if (in_drop(scene, i)) sum += f.position[i], ++count;
  return sum / static_cast<Real>(count);
}

// <z^2> - (<x^2> + <y^2>) / 2 of the drop's particles about their centroid (m^2).
Real drop_quadrupole(const Scene& scene) {
  const FluidState& f = scene.state.fluid;
  const Vec3 c = drop_centroid(scene);
  Real sum = 0;
  Index count = 0;
  for (Index i = 0; i < f.count; ++i) {
    if (!in_drop(scene, i)) continue;
    const Vec3 d = f.position[i] - c;
    sum += d.z() * d.z() - 0.5 * (d.x() * d.x() + d.y() * d.y()), ++count;
  }
  return sum / static_cast<Real>(count);
}

// Lamb's l = 2 frequency of a drop of radius R in a liquid of the same density held in a rigid
// sphere of radius b (potential flow; derivation in docs/validation.md):
//   omega^2 = l (l - 1) (l + 2) sigma / (rho R^3 [1 + (l / (l + 1) + x) / (1 - x)]),  x = (R / b)^(2l + 1).
Real lamb_frequency(Real sigma) {
  const Real x = std::pow(kDrop / kTank, 5);
  return std::sqrt(8 * sigma / (kDensity * std::pow(kDrop, 3) * (1 + (2.0 / 3 + x) / (1 - x))));
}

// Lets the drop settle for 0.1 s with the velocities zeroed after each step.
void settle(Scene& scene) {
  for (int s = 0; s < 200; ++s) {
    test::run_steps(scene, 1);
    for (Vec3& v : scene.state.fluid.velocity) v.setZero();
  }
}

// The natural frequency omega_0 (rad/s) of the l = 2 oscillation of the drop in the weightless
// tank with the interfacial tension sigma. The mode is started with the potential flow of the tank
// solution, v = grad phi: inside phi = a r^2 P_2, outside B (r^2 + c r^-3) P_2 with c = 2 b^5 / 3
// (no flow through the wall) and B = -a x / (1 - x) (the radial velocity continuous at R);
// a = 0.05 omega, so the drop deforms by the same fraction of R at every sigma.
Real oscillation_frequency(Real sigma) {
  Scene scene = drop_in_liquid(sigma, 0);
  FluidState& f = scene.state.fluid;
  settle(scene);
  const Real omega = lamb_frequency(sigma);
  const Real a = 0.05 * omega, x = std::pow(kDrop / kTank, 5), c = 2 * std::pow(kTank, 5) / 3, B = -a * x / (1 - x);
  const Vec3 center = drop_centroid(scene);
  for (Index i = 0; i < f.count; ++i) {
    const Vec3 d = f.position[i] - center;
    const Vec3 grad_r2p2(-d.x(), -d.y(), 2 * d.z());  // grad (z^2 - (x^2 + y^2) / 2)
    if (in_drop(scene, i)) {
      f.velocity[i] = a * grad_r2p2;
    } else {
      const Real r = d.norm(), q = d.z() * d.z() - 0.5 * (d.x() * d.x() + d.y() * d.y());
      f.velocity[i] = B * ((1 + c / std::pow(r, 5)) * grad_r2p2 - 5 * c * q / std::pow(r, 7) * d);
    }
  }
  // 0.6 s at 0.072 N/m, the same number of periods at any sigma (about 1.7).
  const int steps = static_cast<int>(std::lround(1200 * lamb_frequency(0.072) / omega));
  std::vector<Real> t, q;
  for (int s = 1; s <= steps; ++s) {
    test::run_steps(scene, 1);
    t.push_back(s * kDt);
    q.push_back(drop_quadrupole(scene));
  }
  const test::DampedOscillation fit = test::fit_damped_oscillation(t, q);
  std::printf("sigma %.3f N/m: omega_0 %.2f rad/s against Lamb's %.2f in the tank (%+.2f %%); damping ratio %.3f\n", sigma,
              fit.natural(), omega, 100 * (fit.natural() / omega - 1), fit.decay / fit.natural());
  return fit.natural();
}

TEST(FluidInterfacialTension, ADropInALiquidOscillatesAtLambsFrequency) {
  // Lamb's frequency in the tank is 17.9 rad/s at sigma = 0.072 N/m (16.0 % below Rayleigh's for
  // the same drop in air, which moves no liquid around it) and twice that at four times the tension.
  // The particles run 9.9 % slow at 0.072 N/m (7.6-10.8 % at every substep and iteration count
  // tried, 2-6 each, and 8.9 % at r = 0.35 mm) and 5.4 % slow at 0.288 N/m, with a damping ratio of
  // 0.11-0.14 where the same drop in air has 0.06: a drag that matters less at the higher frequency. Most
  // likely the interface's grip: the tangential velocity of the potential flow jumps across the
  // interface, and the particles of the two liquids, interlocked there, resist that slip
  // (docs/validation.md). A change of round-off alone moved each frequency by up to 1 %. Hence 12 %
  // on each frequency, and 10 % on their ratio (2.06-2.12 measured; 2.10 now): the exponent of sigma within
  // 0.5 +- 0.07, where a force of the wrong dimension would give 1 or 0.25.
  const Real low = oscillation_frequency(0.072), high = oscillation_frequency(0.288);
  EXPECT_NEAR(low / lamb_frequency(0.072), 1, 0.12);
  EXPECT_NEAR(high / lamb_frequency(0.288), 1, 0.12);
  EXPECT_NEAR(high / low, 2, 0.2);
}

TEST(FluidInterfacialTension, ARestingDropsPressureJumpIsYoungLaplace) {
  // 2 sigma / R = 14.4 Pa for sigma = 0.072 N/m and R = 1 cm. The pressures (the density
  // multipliers', the mechanical pressure here: neither liquid has Akinci cohesion) are taken
  // without their hydrostatic part rho g y: inside the drop within R / 2 of its centre, and in
  // the surrounding liquid between R + h and b - h (h = 4 r); each averaged over 0.3 s of
  // steps after 0.1 s of settling with the velocities zeroed and 0.1 s free. The drop still sways:
  // a mean over 0.1 s read 15.2 Pa or 15.8 Pa with nothing but the round-off changed, and the
  // running mean settles near 15.1 Pa after 0.3-0.4 s.
  const Real sigma = 0.072;
  Scene scene = drop_in_liquid(sigma, kGravity);
  const FluidState& f = scene.state.fluid;
  settle(scene);
  test::run_steps(scene, 200);
  const Real h = 4 * kParticleRadius;
  Real inside = 0, outside = 0;
  Index n_in = 0, n_out = 0;
  for (int s = 0; s < 600; ++s) {
    test::run_steps(scene, 1);
    const Vec3 center = drop_centroid(scene);
    for (Index i = 0; i < f.count; ++i) {
      const Real p = f.pressure[i] + kDensity * kGravity * f.position[i].y();  // less its hydrostatic part
      const Real from_drop = (f.position[i] - center).norm(), from_tank = kTank - f.position[i].norm();
      if (in_drop(scene, i) && from_drop < 0.5 * kDrop) inside += p, ++n_in;
      if (!in_drop(scene, i) && from_drop > kDrop + h && from_tank > h) outside += p, ++n_out;
    }
  }
  const Real jump = inside / n_in - outside / n_out, laplace = 2 * sigma / kDrop;
  std::printf("pressure jump %.2f Pa against Young-Laplace's %.2f Pa (%+.1f %%)\n", jump, laplace,
              100 * (jump / laplace - 1));
  EXPECT_NEAR(jump / laplace, 1, 0.10);  // the validation target
}

// The error a scene with the two fluids' entries `outer` and `inner` (JSON members) gives, or "".
std::string two_liquids_error(const std::string& outer, const std::string& inner, Real dt = 0.0005) {
  try {
    test::scene_from_json(fmt::format(R"({{"name": "two", "settings": {{"dt": {}}}, "objects": [
      {{"name": "water", "kind": "fluid", "particle_radius": 0.0005, "block": {{"min": [0, 0, 0], "max": [0.004, 0.002, 0.004]}}{}}},
      {{"name": "oil", "kind": "fluid", "particle_radius": 0.0005, "density": 900,
        "block": {{"min": [0, 0.002, 0], "max": [0.004, 0.004, 0.004]}}{}}}]}})",
                                      dt, outer, inner));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FluidInterfacialTension, BadEntriesNameTheirKey) {
  auto expect = [](const std::string& message, const std::vector<std::string>& parts) {
    EXPECT_FALSE(message.empty()) << "accepted";
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  EXPECT_EQ(two_liquids_error(R"(, "interfacial_tension": {"oil": 0.03})", ""), "");
  expect(two_liquids_error(R"(, "interfacial_tension": {"oli": 0.03})", ""),
         {"objects[0].interfacial_tension.oli", "no object 'oli'", "'oil'"});
  expect(two_liquids_error(R"(, "interfacial_tension": {"water": 0.03})", ""), {"no interface with itself"});
  expect(two_liquids_error(R"(, "interfacial_tension": {"oil": -1})", ""), {"interfacial_tension.oil", "out of range"});
  expect(two_liquids_error(R"(, "interfacial_tension": {"oil": 0.03})", R"(, "interfacial_tension": {"water": 0.03})"),
         {"objects[1].interfacial_tension.water", "already gives this interface a tension"});
  expect(two_liquids_error(R"(, "interfacial_tension": [0.03])", ""), {"objects[0].interfacial_tension"});
  // Brackbill's limit with the mean density 950 kg/m^3: sqrt(950 (1e-3)^3 / (2 pi 0.03)) = 2.24 ms.
  expect(two_liquids_error(R"(, "interfacial_tension": {"oil": 0.03})", "", 0.003), {"interfacial_tension.oil", "0.00224"});
}

}  // namespace
}  // namespace moreau
