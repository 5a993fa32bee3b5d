// An emitter's nozzle holds its stream (fluid_emitter.hpp): a very viscous thread hangs from it.
//
// A thread of viscosity mu emitted downward at v0 is held over the nozzle's length and stretches
// under its own weight below it. For a hanging length L carried by its extensional (Trouton)
// stress 3 mu dv/dz, the weight below z gives 3 mu dv/dz = rho g (L - z), so its lowest point moves
// faster than the nozzle by dv = rho g L^2 / (6 mu): 8.4e-5 m/s here (rho = 1000 kg/m^3, 1.6 cm
// below the 4 mm nozzle, mu = 5e3 Pa s; an estimate: the thread is still growing). Held rigidly,
// the thread's first layer, born at the opening at t = 0, is at c - v0 t. Without the nozzle
// nothing carries the stream: it falls freely.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "moreau/fluids/fluid_state.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kOpeningHeight = 0.3, kSpeed = 0.1, kGravity = 9.81;

Scene viscous_thread(const std::string& solver, const std::string& nozzle) {
  return test::scene_from_json(R"({"name": "thread", "settings": {"solver": ")" + solver +
                               R"(", "dt": 0.002, "substeps": 4, "iterations": 4},
    "objects": [
      {"name": "syrup", "kind": "fluid", "particle_radius": 0.001, "viscosity": 5000,
       "emitter": {"shape": "disc", "center": [0, 0.3, 0], "direction": [0, -1, 0], "radius": 0.004,
                   "speed": 0.1)" + nozzle + R"(}}]})");
}

struct ThreadEnd {
  Real lowest;     // m, the lowest particle's height
  Real speed;      // m/s, its downward speed
};

ThreadEnd thread_end(const FluidState& f) {
  Index low = 0;
  for (Index i = 1; i < f.count; ++i)
    if (f.position[i].y() < f.position[low].y()) low = i;
  return {f.position[low].y(), -f.velocity[low].y()};
}

class NozzleOnEverySolver : public ::testing::TestWithParam<std::string> {};

TEST_P(NozzleOnEverySolver, AViscousThreadHangsFromItsNozzle) {
  Scene scene = viscous_thread(GetParam(), "");
  test::run_steps(scene, 100);  // t = 0.2 s: ten layers of 13 particles, the thread 2 cm long
  const FluidState& f = scene.state.fluid;
  ASSERT_EQ(f.count, 10 * 13);
  const Real t = scene.state.time;
  const ThreadEnd end = thread_end(f);
  // The viscosity acts on the velocities after the positions have moved with the weight's
  // velocity change, so a hanging thread creeps down g h_v faster than it is fed, h_v the step of
  // the viscosity solve (the substep under xpbd, the step under nmd): the first layer, free from
  // t = 0.04 s, by g h_v (t - 0.04). First order in h_v: 1.58 mm at two substeps, 0.79 at four.
  const Real h_v = GetParam() == "xpbd" ? 0.0005 : 0.002, sag = kGravity * h_v * (t - 0.04);
  const Real held_course = kOpeningHeight - kSpeed * t;
  std::printf("%s: lowest particle %.3f mm below the held course (the splitting's sag %.3f mm), "
              "moving %.2e m/s faster than the nozzle\n",
              GetParam().c_str(), 1e3 * (held_course - end.lowest), 1e3 * sag, end.speed - kSpeed);
  // Measured 1.5e-4 m/s under xpbd and 2.1e-4 under nmd: about twice Trouton's estimate, as the
  // one-sided density constraint lets the layers part slightly. Bound 5e-4 m/s, six times the
  // estimate; a thread the nozzle did not hold would be nearly 2 m/s faster.
  EXPECT_GE(end.speed - kSpeed, 0);
  EXPECT_LE(end.speed - kSpeed, 5e-4);
  EXPECT_NEAR(end.lowest, held_course - sag, 0.1e-3);  // a twentieth of a lattice spacing

  // The particles still in the nozzle (4r = 4 mm: the two newest layers) move at the emitter's
  // velocity, exactly, on their layers' course: layer k (ids 13k ... 13k + 12), born at
  // t_k = k 2r / v0, is at c - v0 (t - t_k).
  int held = 0;
  for (Index i = 0; i < f.count; ++i) {
    if (f.release_time[i] == 0) continue;
    ++held;
    const Real born = (f.id[i] / 13) * 0.002 / kSpeed;
    EXPECT_EQ(f.velocity[i], Vec3(0, -kSpeed, 0));
    EXPECT_NEAR(f.position[i].y(), kOpeningHeight - kSpeed * (t - born), 1e-12);
  }
  EXPECT_EQ(held, 2 * 13);
}

TEST_P(NozzleOnEverySolver, WithoutANozzleTheThreadFallsFreely) {
  Scene scene = viscous_thread(GetParam(), R"(, "nozzle_length": 0)");
  test::run_steps(scene, 100);
  const Real t = scene.state.time;
  const ThreadEnd end = thread_end(scene.state.fluid);
  std::printf("%s, no nozzle: lowest particle moving at %.4f m/s (free fall from the opening: %.4f)\n",
              GetParam().c_str(), end.speed, kSpeed + kGravity * t);
  // Nothing holds the first layer back: the layers part as they fall (a layer born 20 ms after
  // the one below is more than a kernel radius behind it by then), and the lowest one moves at
  // v0 + g t as a free body does.
  EXPECT_NEAR(end.speed, kSpeed + kGravity * t, 1e-3 * (kSpeed + kGravity * t));
}

INSTANTIATE_TEST_SUITE_P(Solvers, NozzleOnEverySolver, ::testing::Values("xpbd", "nmd"));

}  // namespace
}  // namespace moreau
