// A gas in open air (src/moreau/fluids/ambient_air.hpp): the air carries the gas's weight and
// drags the particles it partly surrounds toward the wind, dv/dt = -k (1 - rho_i / rho0) (v - v_air),
// and a warm gas rises with the Boussinesq part of gravity, -beta (T - T_ref) g.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "moreau/fluids/fluid_heat.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kRadius = 0.005, kGravity = 9.81, kPi = 3.14159265358979323846;

// Air-like gas (1.2 kg/m^3, beta = 1/300 K^-1 about 300 K) filling the block [0, size]^3 (m),
// at `temperature` (K), with drag k = `drag` (1/s) toward `wind` (m/s).
Scene gas_scene(Real size, Real temperature, Real drag, const std::string& wind, Real dt = 0.01, Real mixing = 0) {
  return test::scene_from_json(fmt::format(R"({{"name": "gas", "settings": {{"dt": {}, "substeps": 2, "iterations": 2}},
    "objects": [
      {{"name": "smoke", "kind": "fluid", "particle_radius": {}, "density": 1.2, "viscosity": 0, "xsph": 0,
        "thermal": {{"temperature": {}, "conductivity": 0, "expansion": {}, "reference_temperature": 300}},
        "gas": {{"drag": {}, "wind": {}, "mixing": {}}},
        "block": {{"min": [0, 0, 0], "max": [{}, {}, {}]}}}}]}})",
                                           dt, kRadius, temperature, 1.0 / 300, drag, wind, mixing, size, size, size));
}

Vec3 mean_position(const Scene& scene) {
  const FluidState& f = scene.state.fluid;
  Vec3 sum = Vec3::Zero();
  for (Index i = 0; i < f.count; ++i) sum += f.position[i];
  return sum / static_cast<Real>(f.count);
}

// The mean velocity (m/s) of a lone particle 30 K warm in a wind of 0.5 m/s along x, over the
// second of a run's first 3 s (14 time constants have passed by then).
Vec3 lone_particle_velocity(Real dt) {
  Scene scene = gas_scene(2 * kRadius, 330, 10, "[0.5, 0, 0]", dt);
  EXPECT_EQ(scene.state.fluid.count, 1);
  test::run_steps(scene, std::lround(2 / dt));
  const Vec3 start = scene.state.fluid.position[0];
  test::run_steps(scene, std::lround(1 / dt));
  return scene.state.fluid.position[0] - start;
}

TEST(FluidGas, ALoneWarmParticleRisesAtItsTerminalVelocityAndDriftsWithTheWind) {
  // Buoyancy g beta Delta T = 0.981 m/s^2 up; drag lambda = k (1 - 1/pi) (the particle's own kernel
  // value is the whole of its density, V W(0) = 1/pi of rho0). Terminal velocity v_t = 0.981 / lambda
  // = 0.1439 m/s up, and the wind's 0.5 m/s along x.
  // The buoyancy is applied in each of the S = 2 substeps (length h = dt / S) and the drag once per
  // step. That splitting's steady state is exact: with x = lambda dt, the mean velocity over a step is
  //   v / v_t = x / (e^x - 1) + x (S + 1) / (2 S) = 1 + lambda h / 2 + O(x^2),
  // +1.743 % at dt = 0.01 s and +0.428 % at dt = 0.0025 s: first order, converging to v_t.
  const Real lambda = 10 * (1 - 1 / kPi), terminal = kGravity * 30.0 / 300 / lambda;
  for (Real dt : {0.01, 0.0025}) {
    const Vec3 velocity = lone_particle_velocity(dt);
    const Real x = lambda * dt, S = 2;
    const Real discrete = x / std::expm1(x) + x * (S + 1) / (2 * S);
    std::printf("dt = %.4f s: mean velocity (%.6f, %.6f, %.6f) m/s; v_t %.6f m/s (%+.3f %%, the step's steady state %+.3f %%)\n",
                dt, velocity.x(), velocity.y(), velocity.z(), terminal, 100 * (velocity.y() / terminal - 1),
                100 * (discrete - 1));
    // Bound 1e-6: the velocity has settled to e^-14 of its start, and the displacement over 1 s is
    // summed from 100-400 steps in round-off.
    EXPECT_NEAR(velocity.y() / terminal, discrete, 1e-6);
    // Converging: the error is the first-order term lambda h / 2 and a little of order x^2.
    EXPECT_LT(std::abs(discrete - 1), 0.55 * lambda * dt / S);
    EXPECT_NEAR(velocity.x(), 0.5, 1e-6);  // the drift has settled to e^-14 of the wind
    EXPECT_NEAR(velocity.z(), 0, 1e-12);
  }
}

TEST(FluidGas, GasAtTheAirsTemperatureIsWeightlessAndCoolGasSinks) {
  // A cloud of 6 x 6 x 6 particles at the reference temperature floats where it is (the air carries
  // its weight); 30 K cooler, it sinks, and only its edge particles feel the air's drag.
  Scene neutral = gas_scene(12 * kRadius, 300, 10, "[0, 0, 0]");
  Scene cool = gas_scene(12 * kRadius, 270, 10, "[0, 0, 0]");
  ASSERT_EQ(neutral.state.fluid.count, 216);
  const Vec3 start = mean_position(neutral);
  test::run_steps(neutral, 50);
  test::run_steps(cool, 50);
  const Vec3 moved = mean_position(neutral) - start, sank = mean_position(cool) - start;
  std::printf("neutral cloud's centre moved (%.2e, %.2e, %.2e) m; the cool one's %.4f m in 0.5 s\n", moved.x(),
              moved.y(), moved.z(), sank.y());
  // The neutral cloud spreads (nothing holds a gas together) but its centre stays: the cube is
  // symmetric, so the drag on its edge particles (which alone would not conserve momentum) cancels
  // over opposite faces, and the density solve moves particles in equal and opposite pairs.
  // Bound: 1e-9 m, round-off over 50 steps.
  EXPECT_LT(moved.norm(), 1e-9);
  // The cool cloud sinks at most as fast as free fall at g beta Delta T = 0.981 m/s^2 (0.123 m in
  // 0.5 s; the integrator's own free fall is 1 % more, and the cloud falls 9.4 cm) and faster than a
  // lone particle, whose drag is the largest a particle can have: from
  // rest it falls v_t (t - tau (1 - e^(-t/tau))) = 0.0515 m in 0.5 s (v_t = 0.1439 m/s, tau = 0.147 s).
  const Real t = 0.5, a = kGravity * 30.0 / 300, rate = 10 * (1 - 1 / kPi);
  const Real lone = a / rate * (t - (1 - std::exp(-rate * t)) / rate);
  EXPECT_LT(-sank.y(), 0.5 * a * t * t);
  EXPECT_GT(-sank.y(), lone);
}

TEST(FluidGas, TheAirMixesIntoALoneParticlesSmokeAndHeatAtTheOpenRate) {
  // Mixing m = 2 1/s into a lone particle (open fraction 1 - 1/pi): its smoke concentration and its
  // excess temperature over the air's both decay as exp(-m (1 - 1/pi) t). The step integrates the
  // decay exactly for a constant open fraction, so after 1 s both agree to round-off (bound 1e-12).
  Scene scene = gas_scene(2 * kRadius, 330, 10, "[0, 0, 0]", 0.01, 2);
  test::run_steps(scene, 100);
  const FluidState& f = scene.state.fluid;
  const Real expected = std::exp(-2 * (1 - 1 / kPi) * scene.state.time);
  const Real excess = fluid_temperature(scene.model.fluid.phases[0], f.enthalpy[0]) - 300;
  std::printf("after %.2f s: smoke %.12f, excess temperature %.9f K (expected %.12f and %.9f)\n", scene.state.time,
              f.smoke[0], excess, expected, 30 * expected);
  EXPECT_NEAR(f.smoke[0], expected, 1e-12);
  EXPECT_NEAR(excess, 30 * expected, 30e-12);
}

}  // namespace
}  // namespace moreau
