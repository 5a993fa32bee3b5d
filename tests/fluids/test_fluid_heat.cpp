// Heat in the particle fluids (src/moreau/fluids/fluid_heat.hpp) against the classical solutions of
// the heat equation: a column heated from its floor (the error function), two liquids brought
// into contact (the contact temperature of two half-spaces), and a solid at its melting point
// melted from below (Neumann's solution of the one-phase Stefan problem). The liquid rests in a
// tank 16 particles wide whose side walls insulate; the profiles are read in its middle 8 x 8
// columns, four particle spacings from every side wall. (A particle next to an insulating wall
// misses the neighbours beyond it and conducts 15 % less along the wall.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "moreau/fluids/fluid_heat.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kRadius = 0.0025, kSpacing = 2 * kRadius, kWidth = 0.08;

// The settings of the weightless tests: the liquid rests on its lattice, and heat alone acts.
constexpr const char* kWeightless = R"({"dt": 0.01, "substeps": 2, "gravity": [0, 0, 0]})";

// A tank 8 cm square that reaches 3 cm below its floor, a floor box with the given wall
// temperature (K) or insulating ("null"), and the fluid objects given (a JSON list's entries).
Scene heated_tank(const std::string& floor_temperature, const std::string& fluids,
                  const std::string& settings = kWeightless) {
  const std::string floor = floor_temperature == "null" ? "" : fmt::format(R"(, "temperature": {})", floor_temperature);
  return test::scene_from_json(fmt::format(R"({{"name": "heat", "settings": {},
    "objects": [
      {{"name": "tank", "kind": "collider", "inside": true,
        "shape": {{"type": "box", "center": [0.04, 0.06, 0.04], "half_extents": [0.04, 0.09, 0.04]}}}},
      {{"name": "floor", "kind": "collider"{},
        "shape": {{"type": "box", "center": [0.04, -0.01, 0.04], "half_extents": [0.06, 0.01, 0.06]}}}},
      {}]}})",
                                           settings, floor, fluids));
}

// A fluid entry filling the tank from height y0 to y1 (m).
std::string fluid_layer(const std::string& name, Real y0, Real y1, const std::string& keys) {
  return fmt::format(R"({{"name": "{}", "kind": "fluid", "particle_radius": {}, "xsph": 0, {},
      "block": {{"min": [0, {}, 0], "max": [{}, {}, {}]}}}})",
                     name, kRadius, keys, y0, kWidth, y1, kWidth);
}

bool in_middle(const Vec3& x) {
  return x.x() > 0.02 && x.x() < 0.06 && x.z() > 0.02 && x.z() < 0.06;
}

struct Layer {
  Real height = 0, temperature = 0, liquid_fraction = 0;
  int count = 0;
};

// The middle columns' particles, grouped by lattice layer: mean height, temperature, liquid fraction.
std::map<int, Layer> middle_layers(const Scene& scene) {
  const FluidState& f = scene.state.fluid;
  std::map<int, Layer> layers;
  for (Index i = 0; i < f.count; ++i) {
    if (!in_middle(f.position[i])) continue;
    const FluidPhase& phase = scene.model.fluid.phases[f.phase[i]];
    Layer& l = layers[static_cast<int>(std::lround((f.position[i].y() - kRadius) / kSpacing))];
    l.height += f.position[i].y();
    l.temperature += fluid_temperature(phase, f.enthalpy[i]);
    l.liquid_fraction += fluid_liquid_fraction(phase, f.enthalpy[i]);
    ++l.count;
  }
  for (auto& [k, l] : layers) {
    l.height /= l.count;
    l.temperature /= l.count;
    l.liquid_fraction /= l.count;
  }
  return layers;
}

// The fluids' total enthalpy sum_i m_i H_i (J).
Real total_enthalpy(const Scene& scene) {
  const FluidState& f = scene.state.fluid;
  Real sum = 0;
  for (Index i = 0; i < f.count; ++i) sum += f.mass[i] * f.enthalpy[i];
  return sum;
}

TEST(FluidHeat, AColumnHeatedFromItsFloorFollowsTheErrorFunction) {
  // T(y, t) = T_w + (T_0 - T_w) erf(y / (2 sqrt(alpha t))), alpha = k / (rho c) = 1e-4 m^2/s:
  // the heat has reached 2 cm (2 sqrt(alpha t)) at 1 s, a quarter of the 10 cm column.
  constexpr Real kFloor = 400, kStart = 300, kAlpha = 1e-4;
  Scene scene = heated_tank("400", fluid_layer("water", 0, 0.1,
      R"("density": 1000, "thermal": {"temperature": 300, "conductivity": 100, "specific_heat": 1000})"));
  ASSERT_EQ(scene.state.fluid.count, 16 * 20 * 16);
  test::run_steps(scene, 100);
  const Real t = scene.state.time;
  Real worst = 0;
  for (const auto& [k, l] : middle_layers(scene)) {
    if (l.height > 0.05) break;
    const Real exact = kFloor + (kStart - kFloor) * std::erf(l.height / (2 * std::sqrt(kAlpha * t)));
    std::printf("y = %.4f m: T = %.2f K, erf solution %.2f K\n", l.height, l.temperature, exact);
    worst = std::max(worst, std::abs(l.temperature - exact) / (kFloor - kStart));
  }
  std::printf("largest error %.2f %% of the temperature step\n", 100 * worst);
  // Measured 1.05 %: the profile is 0.4-1.1 K low. The lattice Laplacian is 0.8 % low (its kernel
  // moment is 0.992), and the first steps, while the heat has spread less than a spacing, lag.
  // Bound 2 %, about twice the measured error.
  EXPECT_LT(worst, 0.02);
}

TEST(FluidHeat, TwoLiquidsInContactExchangeTheHeatOfTwoHalfSpaces) {
  // Two half-spaces at T_1 and T_2 brought into contact exchange, per unit area,
  //   Q(t) = 2 (T_1 - T_2) sqrt(t / pi) e_1 e_2 / (e_1 + e_2),   e = sqrt(k rho c)
  // (the contact temperature (e_1 T_1 + e_2 T_2) / (e_1 + e_2) holds at the interface). A hot,
  // light liquid rests on a cold, heavy one that conducts 4 times better and has 3 times its
  // effusivity; the pair conductivity's harmonic mean is what makes the series conductance right.
  // Diffusivities 1e-4 and 1.7e-4 m^2/s: by 1 s the heat has spread 2 and 2.6 cm into 6 cm deep
  // layers. Between insulating walls the total enthalpy is conserved.
  constexpr Real kHot = 360, kCold = 300;
  const Real e_hot = std::sqrt(100.0 * 1000 * 1000), e_cold = std::sqrt(400.0 * 1200 * 2000);
  Scene scene = heated_tank("null",
                            fluid_layer("cold", 0, 0.06,
                                        R"("density": 1200, "thermal": {"temperature": 300, "conductivity": 400, "specific_heat": 2000})") +
                                ", " +
                                fluid_layer("hot", 0.06, 0.12,
                                            R"("density": 1000, "thermal": {"temperature": 360, "conductivity": 100, "specific_heat": 1000})"));
  const Real start = total_enthalpy(scene);
  const FluidState& f = scene.state.fluid;
  auto cold_heat = [&] {  // J gained by the cold liquid's middle columns, per m^2
    Real sum = 0;
    for (Index i = 0; i < f.count; ++i)
      if (f.phase[i] == 0 && in_middle(f.position[i])) sum += f.mass[i] * (f.enthalpy[i] - 2000 * kCold);
    return sum / (0.04 * 0.04);
  };
  test::run_steps(scene, 100);
  const Real t = scene.state.time;
  const Real exact = 2 * (kHot - kCold) * std::sqrt(t / kPi) * e_hot * e_cold / (e_hot + e_cold);
  std::printf("heat into the cold liquid %.4g J/m^2, two half-spaces %.4g J/m^2 (%+.2f %%)\n", cold_heat(), exact,
              100 * (cold_heat() / exact - 1));
  // Measured -2.4 %. The lattice misses a fixed amount of heat in the first steps, while the heat
  // has not yet spread a particle spacing (-6.6, -3.5 and -2.4 % of Q at 0.25, 0.5 and 1 s: about
  // the same amount each time), so the error falls as 1 / sqrt(t). Bound 3 %.
  EXPECT_NEAR(cold_heat() / exact, 1, 0.03);
  const Real drift = std::abs(total_enthalpy(scene) / start - 1);
  std::printf("total enthalpy drift %.2e\n", drift);
  // Each pair's exchange is equal and opposite, so only the rounding of the sum remains
  // (2e-16 to 3e-15 measured).
  EXPECT_LT(drift, 1e-13);
}

// Neumann's one-phase Stefan problem: the melt front of a solid at its melting point T_m with its
// face held at T_w > T_m is at s = 2 lambda sqrt(alpha t), where lambda solves
//   lambda exp(lambda^2) erf(lambda) = St / sqrt(pi),  St = c |T_w - T_m| / L,
// and so is the freezing front of a liquid at T_m on a wall at T_w < T_m.
Real stefan_lambda(Real stefan) {
  Real lo = 0, hi = 3;
  for (int k = 0; k < 100; ++k) {
    const Real mid = 0.5 * (lo + hi);
    (mid * std::exp(mid * mid) * std::erf(mid) < stefan / std::sqrt(kPi) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(FluidHeat, ASolidAtItsMeltingPointMeltsFromAHotFloorAsNeumannsSolution) {
  // St = 1000 (400 - 300) / 1e5 = 1, lambda = 0.620; alpha = 4e-4 m^2/s: the front reaches 1.8,
  // 2.5 and 3.5 cm at 0.5, 1 and 2 s. The melted thickness is the liquid fraction summed over a
  // column: d sum_i phi_i.
  constexpr Real kAlpha = 4e-4;
  const Real lambda = stefan_lambda(1.0);
  EXPECT_NEAR(lambda, 0.6201, 1e-3);  // tabulated for St = 1 (e.g. Alexiades & Solomon 1993)
  Scene scene = heated_tank("400", fluid_layer("wax", 0, 0.1,
      R"("density": 1000, "viscosity": 0.001, "thermal": {"temperature": 300, "conductivity": 400,
         "specific_heat": 1000, "melting_point": 300, "latent_heat": 1e5, "solid_viscosity": 0.01})"));
  Real worst = 0;
  for (const int steps : {50, 50, 100}) {
    test::run_steps(scene, steps);
    const Real t = scene.state.time;
    Real melted = 0;
    for (const auto& [k, l] : middle_layers(scene)) melted += kSpacing * l.liquid_fraction;
    const Real exact = 2 * lambda * std::sqrt(kAlpha * t);
    std::printf("t = %.2f s: melted %.2f mm, Neumann %.2f mm (%+.1f %%)\n", t, 1e3 * melted, 1e3 * exact,
                100 * (melted / exact - 1));
    worst = std::max(worst, std::abs(melted / exact - 1));
  }
  // Measured -1.8, +0.8 and -0.2 %: the enthalpy method on the lattice, whose front advances a
  // layer at a time. Bound 5 %, half the 10 % this validation asks and over twice the worst.
  EXPECT_LT(worst, 0.05);
}

TEST(FluidHeat, ALiquidFreezesOnAColdFloorUnderItsOwnWeightAsNeumannsSolution) {
  // Water-like liquid 1 mK above its melting point on a floor at 200 K, under gravity: St = 1 as
  // above, and the crust is d sum_i (1 - phi_i). Solid particles stay where they froze and the
  // liquid rests on them: the crust must keep the rest density (a solid that carried no multiplier
  // let the liquid crowd into it, 16 % over the rest density, before this was fixed).
  constexpr Real kAlpha = 4e-4;
  const Real lambda = stefan_lambda(1.0);
  Scene scene = heated_tank("200", fluid_layer("water", 0, 0.1,
      R"("density": 1000, "thermal": {"temperature": 300.001, "conductivity": 400, "specific_heat": 1000,
         "melting_point": 300, "latent_heat": 1e5})"),
      R"({"dt": 0.01, "substeps": 10, "iterations": 4})");
  test::run_steps(scene, 100);
  const FluidState& f = scene.state.fluid;
  Real frozen = 0, solid_density = 0;
  int solids = 0;
  for (Index i = 0; i < f.count; ++i) {
    if (!in_middle(f.position[i])) continue;
    const Real phi = fluid_liquid_fraction(scene.model.fluid.phases[0], f.enthalpy[i]);
    frozen += kSpacing * (1 - phi) / 64;  // 8 x 8 middle columns
    if (phi == 0) solid_density += f.density[i], ++solids;
  }
  solid_density /= solids;
  const Real exact = 2 * lambda * std::sqrt(kAlpha * scene.state.time);
  std::printf("frozen %.2f mm, Neumann %.2f mm (%+.1f %%); the crust's density %.1f kg/m^3\n", 1e3 * frozen,
              1e3 * exact, 100 * (frozen / exact - 1), solid_density);
  // Measured -4.5 % (-3.4 % at 0.5 s, -5.8 % at 2 s; weightless, the same crust is within 2 %: the
  // liquid freezes where it moved, off the lattice, where the Laplacian is less exact). Bound 10 %,
  // the tolerance this validation asks.
  EXPECT_NEAR(frozen / exact, 1, 0.10);
  // Measured 999.5 kg/m^3; without a multiplier of the solid's own, 1,160 (a 16 % excess).
  // Bound 1 %, the liquid's own density error in this column (1,001 kg/m^3) with margin.
  EXPECT_NEAR(solid_density / 1000, 1, 0.01);
}

TEST(FluidHeat, FreezingGivesTheSameResultOnOneAndTwoThreads) {
  auto run = [](int threads) {
    Scene scene = heated_tank("200", fluid_layer("water", 0, 0.1,
        R"("density": 1000, "thermal": {"temperature": 300.001, "conductivity": 400, "specific_heat": 1000,
           "melting_point": 300, "latent_heat": 1e5})"),
        fmt::format(R"({{"dt": 0.01, "substeps": 10, "iterations": 4, "threads": {}}})", threads));
    test::run_steps(scene, 10);
    return scene.state.fluid;
  };
  const FluidState one = run(1), two = run(2);
  ASSERT_EQ(one.count, two.count);
  for (Index i = 0; i < one.count; ++i) {
    ASSERT_EQ(one.enthalpy[i], two.enthalpy[i]) << i;
    ASSERT_EQ(one.position[i], two.position[i]) << i;
  }
}

}  // namespace
}  // namespace moreau
