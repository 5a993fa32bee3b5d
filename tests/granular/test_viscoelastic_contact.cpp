// Viscoelastic grain contacts (`contact_compliance` alpha in m/N, `contact_damping` c in N s/m):
// a linear spring-dashpot that only pushes. A grain at rest sinks by alpha times its weight, under
// xpbd and nmd alike; a grain that hits the ground bounces back with the restitution of the
// spring-dashpot, which an accurate integration of its equation of motion gives, and the
// position-level (implicit) step approaches it at first order in the substep.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

constexpr Real kG = 9.81;
constexpr Real kRadius = 0.005, kDensity = 2600;
const Real kMass = kDensity * 4 * kPi / 3 * kRadius * kRadius * kRadius;  // 1.36 g

std::string grain_scene(const std::string& solver, Real dt, int substeps, Real gravity, Real y, Real vy,
                        Real compliance, Real damping) {
  return fmt::format(
      R"({{"name": "spring", "settings": {{"solver": "{}", "dt": {}, "substeps": {}, "duration": 1, "gravity": [0, {}, 0]}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
                  {{"name": "grain", "kind": "granular", "blocks": [{{"min": [0, {}, 0], "max": [0.01, {}, 0.01]}}],
                    "radius": {}, "density": {}, "velocity": [0, {}, 0], "restitution": 1,
                    "contact_compliance": {}, "contact_damping": {}}}],
      "probes": [{{"name": "y", "type": "point", "object": "grain", "vertex": 0, "quantity": "position"}},
                 {{"name": "vy", "type": "point", "object": "grain", "vertex": 0, "quantity": "velocity"}}]}})",
      solver, dt, substeps, -gravity, y - kRadius, y + kRadius, kRadius, kDensity, vy, compliance, damping);
}

// The height of a grain left to rest on the ground for 1 s: a spring of compliance 0.01 m/N
// (k = 100 N/m) with c = 0.3 N s/m (damping ratio 0.41) settles within 0.1 s.
Real resting_height(const std::string& solver, Real dt, int substeps) {
  World w = World::from_json(grain_scene(solver, dt, substeps, kG, kRadius, 0, 0.01, 0.3));
  while (w.time() < 1 - 1e-9) w.step();
  return w.probe_values()[1];  // y of (x, y, z)
}

// At rest the spring carries the weight: C = -alpha m g. Both steps hold it exactly: XPBD's
// compliant row at rest gives lambda = m g h^2 with C = -alpha~ lambda (one iteration suffices,
// the predicted sag h^2 g is pushed back), and SPOOK's row gives Sigma lambda^ = -a C. The only
// error left is rounding in positions near 5 mm: 1e-12 m against a sink of 0.13 mm.
TEST(ViscoelasticContact, AGrainAtRestSinksByItsComplianceTimesItsWeight) {
  const Real sink = 0.01 * kMass * kG;
  for (const char* solver : {"xpbd", "nmd"}) {
    const Real y = resting_height(solver, 0.005, 10);
    std::printf("%s: rests %.6e m deep (alpha m g = %.6e m)\n", solver, kRadius - y, sink);
    EXPECT_NEAR(kRadius - y, sink, 1e-12) << solver;
  }
}

// The same grain resting on a fixed rigid box instead of the ground (the particle-body contact
// of the grain's spring): it sinks by alpha m g too, under both solvers.
TEST(ViscoelasticContact, AGrainOnARigidBodySinksByItsComplianceTimesItsWeight) {
  const Real sink = 0.01 * kMass * kG;
  for (const char* solver : {"xpbd", "nmd"}) {
    World w = World::from_json(fmt::format(
        R"({{"name": "on_a_box", "settings": {{"solver": "{}", "dt": 0.005, "substeps": 10, "duration": 1}},
        "objects": [{{"name": "table", "kind": "rigid_body", "fixed": true,
                      "shape": {{"type": "box", "half_extents": [0.1, 0.05, 0.1]}}, "position": [0, -0.05, 0]}},
                    {{"name": "grain", "kind": "granular", "blocks": [{{"min": [0, 0, 0], "max": [0.01, 0.01, 0.01]}}],
                      "radius": {}, "density": {}, "contact_compliance": 0.01, "contact_damping": 0.3}}],
        "probes": [{{"name": "y", "type": "point", "object": "grain", "vertex": 0, "quantity": "position"}}]}})",
        solver, kRadius, kDensity));
    while (w.time() < 1 - 1e-9) w.step();
    const Real y = w.probe_values()[1];
    std::printf("%s: rests %.6e m deep in the rigid box (alpha m g = %.6e m)\n", solver, kRadius - y, sink);
    EXPECT_NEAR(kRadius - y, sink, 1e-12) << solver;
  }
}

// Two grains stacked on the ground: the lower spring carries both weights, the upper one the top
// grain's, along the line of centres (the lattice's jitter tilts it by up to 0.4 degrees; friction
// and rolling resistance hold the tilted stack and carry the rest). The settled stack holds both
// exactly under nmd, whose solve of the contacts converges: to 4e-15 m with 200 sweeps a step (the
// default 50 leave 1e-11 m, the grains' turning rows converging more slowly). Under xpbd each substep's Gauss-Seidel
// sweeps start from zero multipliers, and the springs reach their loads as the sweeps converge:
// with 20 iterations to within 1e-11 m (4 leave the upper one 2e-9 m short). With one iteration
// the stack topples, hard or soft: the pile creep of one iteration (docs/scene-format.md).
TEST(ViscoelasticContact, AStackOfTwoGrainsCompressesEachSpringByTheWeightAboveIt) {
  const Real alpha = 0.01, c = 0.3;
  for (const char* solver : {"xpbd", "nmd"}) {
    World w = World::from_json(fmt::format(
        R"({{"name": "stack", "settings": {{"solver": "{}", "dt": 0.005, "substeps": 10, "iterations": 20,
                                           "nmd": {{"iterations": 200}}, "duration": 2}},
        "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
                    {{"name": "grains", "kind": "granular", "blocks": [{{"min": [0, 0, 0], "max": [0.01, 0.0204, 0.01]}}],
                      "radius": {}, "density": {}, "contact_compliance": {}, "contact_damping": {}}}],
        "probes": [{{"name": "low", "type": "point", "object": "grains", "vertex": 0, "quantity": "position"}},
                   {{"name": "high", "type": "point", "object": "grains", "vertex": 1, "quantity": "position"}}]}})",
        solver, kRadius, kDensity, alpha, c));
    while (w.time() < 2 - 1e-9) w.step();
    const std::vector<Real> p = w.probe_values();
    const Vec3 low(p[0], p[1], p[2]), high(p[3], p[4], p[5]);
    const Real ground_sink = kRadius - low.y(), pair_sink = 2 * kRadius - (high - low).norm();
    const Real pair_load = kMass * kG * (high - low).normalized().y();  // the weight along the line of centres
    std::printf("%s: ground spring %.6e m (2 alpha m g = %.6e), pair spring %.6e m (alpha m g n_y = %.6e)\n", solver,
                ground_sink, 2 * alpha * kMass * kG, pair_sink, alpha * pair_load);
    EXPECT_NEAR(ground_sink, 2 * alpha * kMass * kG, 1e-11) << solver;
    EXPECT_NEAR(pair_sink, alpha * pair_load, 1e-11) << solver;
  }
}

// The restitution of a linear spring-dashpot that only pushes: the overlap d obeys
// m d'' = -max(k d + c d', 0) from d = 0, d' = v0; the grain leaves when the force first vanishes
// (the dashpot lets go before the spring is relaxed) with the speed it has then. Integrated by
// RK4 with steps of 1e-4 of the contact's period, which is exact to 1e-12 here.
Real spring_dashpot_restitution(Real m, Real k, Real c, Real v0) {
  const Real step = 1e-4 * 2 * kPi * std::sqrt(m / k);
  auto acceleration = [&](Real d, Real v) { return -std::max(k * d + c * v, 0.0) / m; };
  Real d = 0, v = v0;
  while (true) {
    const Real k1x = v, k1v = acceleration(d, v);
    const Real k2x = v + 0.5 * step * k1v, k2v = acceleration(d + 0.5 * step * k1x, v + 0.5 * step * k1v);
    const Real k3x = v + 0.5 * step * k2v, k3v = acceleration(d + 0.5 * step * k2x, v + 0.5 * step * k2v);
    const Real k4x = v + step * k3v, k4v = acceleration(d + step * k3x, v + step * k3v);
    d += step / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += step / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (v < 0 && (d <= 0 || k * d + c * v <= 0)) return -v / v0;
  }
}

// The rebound speed of a grain thrown at 1 m/s onto the ground without gravity.
Real rebound(const std::string& solver, Real dt, int substeps, Real compliance, Real damping) {
  World w = World::from_json(grain_scene(solver, dt, substeps, 0, kRadius + 0.001, -1, compliance, damping));
  while (w.time() < 0.02 - 1e-9) w.step();
  return w.probe_values()[4];  // v_y of (v_x, v_y, v_z)
}

// k = 1000 N/m, c = 0.467 N s/m (damping ratio 0.2): the contact lasts 3.7 ms and the grain
// sinks 1 mm. The contact's restitution (e = 0.56; the grain's `restitution` 1 is not used by a
// spring) is the spring-dashpot's. The position-level step is backward Euler on the oscillator,
// which loses about pi omega h / 2 of the speed to numerical damping: 1.3 % at omega h = 0.0086
// (h = 10 us). Both steps stay within 2 % at h = 10 us, and the error shrinks at least in
// proportion to h: at h / 2 it is at most 0.6 of it (0.55 under xpbd, 0.50 under nmd; the contact
// also starts within a substep of its true time).
TEST(ViscoelasticContact, AGrainBouncesWithTheRestitutionOfItsSpringAndDashpot) {
  const Real k = 1000, c = 0.2 * 2 * std::sqrt(k * kMass);
  const Real e = spring_dashpot_restitution(kMass, k, c, 1.0);
  struct Run {
    const char* solver;
    Real dt;
    int substeps;
  };
  for (const auto& [coarse, fine] : {std::pair<Run, Run>{{"xpbd", 1e-3, 100}, {"xpbd", 1e-3, 200}},
                                     std::pair<Run, Run>{{"nmd", 1e-5, 1}, {"nmd", 5e-6, 1}}}) {
    const Real e_coarse = rebound(coarse.solver, coarse.dt, coarse.substeps, 1 / k, c);
    const Real e_fine = rebound(fine.solver, fine.dt, fine.substeps, 1 / k, c);
    const Real error_coarse = e_coarse / e - 1, error_fine = e_fine / e - 1;
    std::printf("%s: e = %.5f at h = %.0e s (%+.3f %%), %.5f at h / 2 (%+.3f %%); spring-dashpot e = %.5f\n",
                coarse.solver, e_coarse, coarse.dt / coarse.substeps, 100 * error_coarse, e_fine, 100 * error_fine, e);
    EXPECT_LT(std::abs(error_coarse), 0.02) << coarse.solver;
    EXPECT_LT(std::abs(error_fine), 0.6 * std::abs(error_coarse)) << coarse.solver;
  }
}

// A dashpot without a spring, and a negative compliance, are refused with their paths.
TEST(ViscoelasticContact, ADashpotWithoutASpringIsRefused) {
  for (const char* keys : {R"("contact_damping": 0.3)", R"("contact_compliance": -0.01)"}) {
    try {
      World::from_json(fmt::format(R"({{"name": "bad", "settings": {{"dt": 0.001, "duration": 1}},
          "objects": [{{"name": "sand", "kind": "granular", "blocks": [{{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}}],
                       "radius": 0.01, {}}}]}})",
                                   keys));
      ADD_FAILURE() << "no error for " << keys;
    } catch (const std::exception& e) {
      const std::string key = std::string(keys).substr(1, std::string(keys).find('"', 1) - 1);
      std::printf("%s\n", e.what());
      EXPECT_NE(std::string(e.what()).find("objects[0]." + key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace moreau
