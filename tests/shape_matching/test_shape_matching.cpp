// Shape matching (Mueller et al. 2005): particles pulled towards the best rigid fit of their rest
// shape. A deformed object returns to its rest shape; a spinning, drifting one keeps its momentum.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/shape_matching/shape_matching.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

// A 12 cm cube of 6 x 6 x 6 particles (r = 1 cm, 1000 kg/m^3), no gravity (or a cube `size` m wide).
std::string cube_scene(const std::string& extra, Real size = 0.12) {
  return fmt::format(R"({{"name": "cube", "settings": {{"dt": 0.01, "substeps": 10, "duration": 2, "gravity": [0, 0, 0]}},
      "objects": [{{"name": "cube", "kind": "shape_matched", "blocks": [{{"min": [0, 0, 0], "max": [{}, {}, {}]}}],
                    "radius": 0.01{}}}],
      "probes": [{{"name": "p", "type": "momentum", "object": "cube", "quantity": "linear"}},
                 {{"name": "c", "type": "center_of_mass", "object": "cube"}},
                 {{"name": "e", "type": "energy", "object": "cube", "quantity": "elastic"}}]}})",
                     size, size, size, extra);
}

std::vector<Vec3> positions(World& w) {
  const StateArray x = w.array("particle.position");
  std::vector<Vec3> out(x.count);
  for (long i = 0; i < x.count; ++i) out[i] = Vec3(x.values[3 * i], x.values[3 * i + 1], x.values[3 * i + 2]);
  return out;
}

// RMS distance of x from the best rigid placement of the rest shape (the shape error), m.
Real shape_error(const std::vector<Vec3>& x, const std::vector<Vec3>& rest) {
  Vec3 c = Vec3::Zero(), c0 = Vec3::Zero();
  for (size_t i = 0; i < x.size(); ++i) c += x[i], c0 += rest[i];
  c /= x.size(), c0 /= x.size();
  Mat3 A = Mat3::Zero();
  for (size_t i = 0; i < x.size(); ++i) A += (x[i] - c) * (rest[i] - c0).transpose();
  const Mat3 R = polar_rotation(A);
  Real sum = 0;
  for (size_t i = 0; i < x.size(); ++i) sum += (x[i] - c - R * (rest[i] - c0)).squaredNorm();
  return std::sqrt(sum / x.size());
}

void scramble(World& w, Real amount, std::uint64_t seed) {
  StateArray x = w.array("particle.position");
  std::mt19937_64 draw(seed);
  for (double& v : x.values) v += amount * (2 * static_cast<Real>(draw() >> 11) * 0x1.0p-53 - 1);
}

// Sets every particle moving with `drift` and spinning at `omega` about the cube's centre.
void set_drift_and_spin(World& w, const Vec3& drift, const Vec3& omega) {
  const std::vector<Vec3> x = positions(w);
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : x) c += p;
  c /= x.size();
  StateArray v = w.array("particle.velocity");
  for (size_t i = 0; i < x.size(); ++i) {
    const Vec3 u = drift + omega.cross(x[i] - c);
    for (int k = 0; k < 3; ++k) v.values[3 * i + k] = u[k];
  }
}

// Angular momentum about the centre of particles of equal mass, per unit particle mass.
Vec3 angular_momentum_per_mass(World& w) {
  const std::vector<Vec3> x = positions(w);
  const StateArray v = w.array("particle.velocity");
  Vec3 center = Vec3::Zero(), L = Vec3::Zero();
  for (const Vec3& p : x) center += p;
  center /= x.size();
  for (size_t i = 0; i < x.size(); ++i)
    L += (x[i] - center).cross(Vec3(v.values[3 * i], v.values[3 * i + 1], v.values[3 * i + 2]));
  return L;
}

TEST(ShapeMatching, PolarRotationIsTheRotationOfAStretchedTurn) {
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Mat3 S;
  S << 2, 0.3, 0.1, 0.3, 1.5, -0.2, 0.1, -0.2, 0.8;  // symmetric positive definite
  EXPECT_LT((polar_rotation(R * S) - R).norm(), 1e-12);
  // A reflection: the nearest rotation, det +1.
  EXPECT_NEAR(polar_rotation(Vec3(1, 1, -1).asDiagonal()).determinant(), 1, 1e-14);
}

// Particles scattered by up to 1 cm about the cube's lattice come back to a rigid placement of
// its rest shape when the clusters are rigid: one cluster in one projection (to round-off), 27
// overlapping ones (Gauss-Seidel, each fit undoing part of the last) to 1e-6 of the scatter in
// 0.1 s.
TEST(ShapeMatching, ARigidObjectReturnsToItsRestShapeAtOnce) {
  for (const std::string& extra : {std::string(""), std::string(R"(, "clusters": {"radius": 0.05, "spacing": 0.05})")}) {
    World w = World::from_json(cube_scene(extra));
    const std::vector<Vec3> rest = positions(w);
    scramble(w, 0.01, 3);
    const Real before = shape_error(positions(w), rest);
    w.step();
    const Real after_one = shape_error(positions(w), rest);
    while (w.time() < 0.1 - 1e-9) w.step();
    const Real after = shape_error(positions(w), rest);
    std::printf("rigid cube scattered by 1 cm (%s): shape error %.3e m, after one step %.3e m, after 0.1 s %.3e m\n",
                extra.empty() ? "one cluster" : "27 clusters", before, after_one, after);
    EXPECT_LT(extra.empty() ? after_one : after, (extra.empty() ? 1e-12 : 1e-6) * before) << extra;
  }
}

// A compliant object (one cluster, f = 5 Hz) scattered by 1 cm oscillates about its rest shape:
// each particle's offset from its goal is an oscillator x'' = -omega^2 (x - g), which XPBD's
// projection integrates by implicit Euler (s = omega^2 h^2 / (1 + omega^2 h^2) is exactly its
// step). The RMS shape error therefore follows |cos(omega_h t)| e0 (1 + omega^2 h^2)^(-t / 2h),
// omega_h = atan(omega h)/h: near zero a quarter period in (t = 0.05 s) and back at e0 times the
// decay half a period in (t = 0.1 s; 0.9845 at h = 1 ms). Tolerances: 2 % of e0 at the node and 0.5 % of
// the predicted amplitude at the crest (the goals themselves move a little as the fit turns).
TEST(ShapeMatching, ACompliantObjectOscillatesAboutItsRestShapeAtItsFrequency) {
  World w = World::from_json(cube_scene(R"(, "frequency": 5)"));  // particles of (2 cm)^3 x 1000 kg/m^3 = 8 g
  const std::vector<Vec3> rest = positions(w);
  scramble(w, 0.01, 3);
  const Real e0 = shape_error(positions(w), rest), h = 0.001, omega = 2 * kPi * 5;
  // The clusters' elastic energy, 1/2 sum m omega^2 |x - g|^2 = 1/2 m omega^2 N e0^2 for one cluster
  // of equal masses (its goals are the best rigid placement that e0 measures).
  const Real elastic = w.probe_values()[6], expected = 0.5 * 0.008 * omega * omega * 216 * e0 * e0;
  std::printf("scattered 5 Hz cube: elastic energy %.9e J, 1/2 m omega^2 N e0^2 = %.9e J\n", elastic, expected);
  EXPECT_NEAR(elastic / expected, 1, 1e-9);
  auto at = [&](Real t) {
    while (w.time() < t - 1e-9) w.step();
    return shape_error(positions(w), rest);
  };
  const Real node = at(0.05), crest = at(0.1);
  const Real decay = std::pow(1 + omega * omega * h * h, -0.1 / (2 * h));
  const Real phase = std::cos(std::atan(omega * h) / h * 0.1);
  std::printf("5 Hz cube scattered by 1 cm (shape error %.4e m): %.4e m a quarter period in, %.4e m half a period in "
              "(implicit Euler: %.4e m, %+.2f %%)\n", e0, node, crest, e0 * decay * std::abs(phase),
              100 * (crest / (e0 * decay * std::abs(phase)) - 1));
  EXPECT_LT(node, 0.02 * e0);
  EXPECT_NEAR(crest / (e0 * decay * std::abs(phase)), 1, 0.005);

  // More iterations solve the same implicit step (the multiplier accumulates; the first iteration
  // already meets the step for one cluster, whose fit the uniform pull leaves unturned): the
  // crest is the same to round-off, not a stiffer object's.
  World four = World::from_json(cube_scene(R"(, "frequency": 5)"), {"settings.iterations=4"});
  scramble(four, 0.01, 3);
  while (four.time() < 0.1 - 1e-9) four.step();
  const Real crest_four = shape_error(positions(four), rest);
  std::printf("the same with 4 iterations: %.10e m (1 iteration: %.10e m)\n", crest_four, crest);
  EXPECT_NEAR(crest_four, crest, 1e-9 * crest);
}

// The cube drifts at 1 m/s and spins at 5 rad/s about a tilted axis. Measured from the end of its
// first step to 1.01 s: linear momentum stays to 1e-9 (every projection moves the particles by
// mass-weighted offsets that sum to zero; the velocity (x - x_start)/h loses ~1e-13 m/s a substep
// to the digits of x ~ 1 m over h = 1 ms). Angular momentum about the centre of mass keeps its
// direction to 1e-9 rad, and its size follows what the position-level velocity predicts: after a
// turn by D in a substep, the prediction 2 x_n - x_(n-1) lies at the angle
// D' = atan(sin D / (2 - cos D)) = D (1 - D^2 + O(D^4)) past x_n, and the fit (exactly that angle,
// the cube's inertia being isotropic) turns by it; the chords' angular momentum is r^2 sin D / h.
// Iterating D from atan(omega h) (the first substep, from the tangent velocity) gives the ratio
// sin D_1010 / sin D_10, which the measured one matches to 1e-4 (0.4 % of the loss; it is 2.3e-5).
TEST(ShapeMatching, MomentumIsConserved) {
  World w = World::from_json(cube_scene(""));
  const Real spin = 5, h = 0.001;
  set_drift_and_spin(w, Vec3(1, 0, 0), spin * Vec3(1, 2, 0.5).normalized());
  auto angular = [&]() { return angular_momentum_per_mass(w); };
  auto linear = [&]() { return Vec3(w.probe_values()[0], w.probe_values()[1], w.probe_values()[2]); };
  w.step();
  const Vec3 p0 = linear(), L0 = angular();
  while (w.time() < 1 + 0.01 - 1e-9) w.step();
  const Vec3 p1 = linear(), L1 = angular();
  const Real direction = L1.normalized().cross(L0.normalized()).norm();
  Real turn = std::atan(spin * h), turn_at_start = 0;
  for (int k = 1; k <= 1010; ++k) {
    if (k == 10) turn_at_start = turn;
    turn = std::atan2(std::sin(turn), 2 - std::cos(turn));
  }
  const Real predicted = std::sin(turn) / std::sin(turn_at_start);
  std::printf("spinning cube: linear momentum change %.2e of it; angular momentum x %.8f (predicted %.8f), direction "
              "turned %.2e rad\n", (p1 - p0).norm() / p0.norm(), L1.norm() / L0.norm(), predicted, direction);
  EXPECT_LT((p1 - p0).norm(), 1e-9 * p0.norm());
  EXPECT_NEAR(L1.norm() / L0.norm(), predicted, 1e-4);
  EXPECT_LT(direction, 1e-9);
}

// Dropped on the ground, a rigid shape-matched cube comes to rest on its bottom particles: its
// centre at half its height (0.06 m) within 0.1 mm, a hundredth of a particle radius (under xpbd
// one contact pass per substep leaves the weight pressing the bottom layer in by about 12 um;
// under nmd the contacts' compliance of 1e-7 m/N by far less), and still (kinetic energy below
// 1e-6 J, the energy of a 1.7 kg cube moving at 1 mm/s).
TEST(ShapeMatching, ACubeRestsOnTheGround) {
  for (const std::string solver : {"xpbd", "nmd"}) {
    World w = World::from_json(R"({"name": "drop", "settings": {"dt": 0.005, "substeps": 10, "duration": 2},
        "objects": [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}},
                    {"name": "cube", "kind": "shape_matched", "blocks": [{"min": [0, 0.1, 0], "max": [0.12, 0.22, 0.12]}],
                     "radius": 0.01}],
        "probes": [{"name": "c", "type": "center_of_mass", "object": "cube"},
                   {"name": "k", "type": "energy", "object": "cube", "quantity": "kinetic"}]})",
                               {"settings.solver=" + solver});
    while (w.time() < 1.5 - 1e-9) w.step();
    const std::vector<double> v = w.probe_values();
    std::printf("cube dropped 0.1 m (%s): centre at %.6f m (0.06), kinetic energy %.2e J\n", solver.c_str(), v[1], v[3]);
    EXPECT_NEAR(v[1], 0.06, 1e-4) << solver;
    EXPECT_LT(v[3], 1e-6) << solver;
  }
}

// Under nmd, each particle's offset from its goal is a block of rows (shape_match_rows.hpp). A
// rigid cube scattered by 1 cm is pulled back to a rigid placement of its rest shape: SPOOK
// removes a hard row's violation over about its relaxation of 2 steps, so after 0.1 s (10 steps
// of 10 ms) the shape error is below 1e-3 of the scatter, with one cluster and with 27, under
// projected Gauss-Seidel; the factored methods solve the same rows (a rigid cluster's repeat
// each other exactly six times: shape_match_rows.hpp) and do the same on an 8 cm cube.
TEST(ShapeMatching, UnderNmdARigidObjectReturnsToItsRestShape) {
  struct Case {
    std::string method, extra;
    Real size;
  };
  const std::string clusters = R"(, "clusters": {"radius": 0.05, "spacing": 0.05})";
  for (const Case& c : {Case{"pgs", "", 0.12}, Case{"pgs", clusters, 0.12}, Case{"direct", "", 0.08},
                        Case{"hybrid", clusters, 0.08}}) {
    const std::string extra = c.extra;
    World w = World::from_json(cube_scene(extra, c.size), {"settings.solver=nmd", "settings.nmd.method=" + c.method});
    const std::vector<Vec3> rest = positions(w);
    scramble(w, 0.01, 3);
    const Real before = shape_error(positions(w), rest);
    std::vector<Real> errors;
    while (w.time() < 0.1 - 1e-9) {
      w.step();
      errors.push_back(shape_error(positions(w), rest));
    }
    std::printf("nmd (%s): rigid %.0f cm cube scattered by 1 cm (%s): shape error %.3e m; after 1, 2, 5, 10 steps %.3e, "
                "%.3e, %.3e, %.3e m\n", c.method.c_str(), 100 * c.size, extra.empty() ? "one cluster" : "clusters", before,
                errors[0], errors[1], errors[4], errors[9]);
    EXPECT_LT(errors.back(), 1e-3 * before) << c.method << extra;
  }
}

// Under nmd a compliant row of compliance eps = 1/(m omega^2) is SPOOK's spring with the dashpot
// tau / eps beside it, tau = settings.nmd.stabilization steps (2 h): each particle's offset from
// its goal is the damped oscillator x'' = -omega^2 (x + tau x'), damping ratio
// zeta = omega tau / 2 (0.0314 for 5 Hz at h = 1 ms), whose amplitude falls as exp(-zeta omega t):
// 0.906 and 0.821 of e0 half a period and a period in. The step itself is SPOOK's recurrence for
// one offset x with velocity v (nmd_system.hpp, unit mass): l = (-a x + (b - 1) v) / (1 + S),
// v += l, x += h v, iterated here from (e0, 0); the 5 Hz cube scattered by 1 cm follows it to
// 0.2 % of e0 at the quarter-period node (1.65 % of e0 there, where the continuous oscillator is
// at zeta exp(-zeta pi / 2) = 3.0 %: the step's phase) and to 0.2 % of the predicted amplitude at
// the crests (the goals move a little as the fit turns; measured within 1e-4).
TEST(ShapeMatching, UnderNmdACompliantObjectOscillatesWithSpooksDamping) {
  World w = World::from_json(cube_scene(R"(, "frequency": 5)"), {"settings.solver=nmd", "settings.dt=0.001"});
  const std::vector<Vec3> rest = positions(w);
  scramble(w, 0.01, 3);
  const Real e0 = shape_error(positions(w), rest), omega = 2 * kPi * 5, zeta = omega * 2 * 0.001 / 2;
  auto at = [&](Real t) {
    while (w.time() < t - 1e-9) w.step();
    return shape_error(positions(w), rest);
  };
  const Real node = at(0.05), crest = at(0.1), second = at(0.2);
  const Real decay = std::exp(-zeta * omega * 0.1), decay2 = std::exp(-zeta * omega * 0.2);
  // SPOOK's recurrence (d = 2): a = 4 / (h (1 + 4d)), b = 1 / (1 + 4d), S = 4 eps / (h^2 (1 + 4d)).
  const Real h = 0.001, d = 2, a = 4 / (h * (1 + 4 * d)), b = 1 / (1 + 4 * d), S = 4 / (omega * omega * h * h * (1 + 4 * d));
  std::vector<Real> offset{1};
  for (Real x = 1, v = 0; offset.size() <= 200;) {
    v += (-a * x + (b - 1) * v) / (1 + S);
    x += h * v;
    offset.push_back(x);
  }
  std::printf("nmd 5 Hz cube scattered by 1 cm (shape error %.4e m): %.4f, %.4f and %.4f of it a quarter, half and whole "
              "period in; SPOOK's step %.4f, %.4f, %.4f; the continuous oscillator's amplitude %.4f, %.4f\n",
              e0, node / e0, crest / e0, second / e0, std::abs(offset[50]), std::abs(offset[100]), std::abs(offset[200]),
              decay, decay2);
  EXPECT_NEAR(node / e0, std::abs(offset[50]), 0.002);
  EXPECT_NEAR(crest / e0 / std::abs(offset[100]), 1, 0.002);
  EXPECT_NEAR(second / e0 / std::abs(offset[200]), 1, 0.002);
}

// Under nmd a drifting, spinning rigid cube keeps its momentum: the rows leave every rigid motion
// exactly free (shape_match_rows.hpp), so their impulses exert no force and no torque about the
// mass centre, and the step's straight-line update keeps a free particle's angular momentum. What
// remains is rounding: linear and angular momentum and the spin's direction to 1e-9 over 1 s.
TEST(ShapeMatching, UnderNmdMomentumIsConserved) {
 for (const std::string method : {"pgs", "direct", "hybrid"}) {
  World w = World::from_json(cube_scene("", method == "pgs" ? 0.12 : 0.08),
                             {"settings.solver=nmd", "settings.dt=0.005", "settings.nmd.method=" + method});
  const std::vector<Vec3> x0 = positions(w);
  set_drift_and_spin(w, Vec3(1, 0, 0), 5 * Vec3(1, 2, 0.5).normalized());
  auto angular = [&]() { return angular_momentum_per_mass(w); };
  auto linear = [&]() { return Vec3(w.probe_values()[0], w.probe_values()[1], w.probe_values()[2]); };
  w.step();
  const Vec3 p0 = linear(), L0 = angular();
  while (w.time() < 1 - 1e-9) w.step();
  const Vec3 p1 = linear(), L1 = angular();
  const Real direction = L1.normalized().cross(L0.normalized()).norm();
  std::printf("nmd (%s) spinning cube: linear momentum change %.2e of it; angular momentum x %.12f, direction turned "
              "%.2e rad; shape error %.2e m\n", method.c_str(), (p1 - p0).norm() / p0.norm(), L1.norm() / L0.norm(),
              direction, shape_error(positions(w), x0));
  EXPECT_LT((p1 - p0).norm(), 1e-9 * p0.norm()) << method;
  EXPECT_NEAR(L1.norm() / L0.norm(), 1, 1e-9) << method;
  EXPECT_LT(direction, 1e-9) << method;
 }
}

TEST(ShapeMatching, BadScenesAreRefusedWithTheirPath) {
  auto message = [](const std::string& object, const std::string& solver = "xpbd") {
    try {
      World::from_json(fmt::format(R"({{"name": "bad", "settings": {{"solver": "{}", "dt": 0.001, "duration": 1}},
          "objects": [{}]}})", solver, object));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string cube = R"({"name": "c", "kind": "shape_matched", "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}], "radius": 0.01)";
  // Under nmd one cluster of 11^3 = 1331 particles is refused (its rows grow with its size squared).
  const std::string big = R"({"name": "c", "kind": "shape_matched", "blocks": [{"min": [0, 0, 0], "max": [0.22, 0.22, 0.22]}], "radius": 0.01)";
  EXPECT_EQ(message(cube + "}", "nmd"), "no error");
  EXPECT_NE(message(big + "}", "nmd").find("settings.solver"), std::string::npos);
  EXPECT_NE(message(big + "}", "nmd").find("at most 512 particles"), std::string::npos);
  EXPECT_EQ(message(big + R"(, "clusters": {"radius": 0.05}})", "nmd"), "no error");
  EXPECT_NE(message(cube + R"(, "frequency": 0})").find("objects[0].frequency"), std::string::npos);
  EXPECT_NE(message(cube + R"(, "clusters": {"radius": 0.005, "spacing": 0.1}})").find("objects[0].clusters.radius"), std::string::npos);
  EXPECT_NE(message(R"({"name": "c", "kind": "shape_matched", "blocks": [{"min": [0, 0, 0], "max": [0.01, 0.1, 0.1]}], "radius": 0.01})")
                .find("objects[0].blocks[0].max"), std::string::npos);
}

}  // namespace
}  // namespace moreau
