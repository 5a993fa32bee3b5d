// Clumps: grains made of two to four overlapping spheres held rigid by shape matching. They are
// placed without overlap, stay rigid while they pile up under both formulations, and pile
// steeper than single spheres of the same friction.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

constexpr Real kRadius = 0.005;

Vec3 at(const StateArray& x, long p) { return Vec3(x.values[3 * p], x.values[3 * p + 1], x.values[3 * p + 2]); }

std::string clump_scene(int spheres, const std::string& solver, const std::string& fill) {
  return fmt::format(R"({{"name": "clumps", "settings": {{"solver": "{}", "dt": 0.005, "substeps": 10, "iterations": 4,
      "duration": 2}}, "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
      {{"name": "sand", "kind": "granular", {}, "radius": 0.005, "rolling_resistance": 0,
        "clump": {{"spheres": {}, "spacing": 1}}}}]}})",
                     solver, fill, spheres);
}

// The deepest overlap of spheres of different clumps, and the largest error of a clump's sphere
// distance from s r = r, m.
struct ClumpCheck {
  Real overlap = -1e300, distance_error = 0;
};

ClumpCheck check(const StateArray& x, int spheres) {
  ClumpCheck c;
  const long n = x.count;
  for (long i = 0; i < n; ++i)
    for (long j = i + 1; j < n; ++j) {
      const Real d = (at(x, i) - at(x, j)).norm();
      if (i / spheres == j / spheres) c.distance_error = std::max(c.distance_error, std::abs(d - kRadius));
      else c.overlap = std::max(c.overlap, 2 * kRadius - d);
    }
  return c;
}

// On the lattice, every clump's spheres are exactly s r apart and no two clumps overlap. Dropped
// 0.2 m as a block of clumps (125 pairs, 64 triangles or tetrahedra), they pile on the ground
// and keep their shape: after 1 s each clump's sphere distance is within 0.5 % of r of its rest
// value under xpbd (measured 0.11 %: the contacts' sweep after the clusters' fit leaves its last
// corrections in the shape) and 3 % under nmd (measured 1.7 %: SPOOK relaxes the hard rows over
// 2 steps, and 50 Gauss-Seidel sweeps share them with the contacts), and clumps overlap by less
// than 5 % of r.
TEST(GranularClumps, ClumpsArePlacedApartAndStayRigid) {
  for (int spheres : {2, 3, 4}) {
    for (const std::string solver : {"xpbd", "nmd"}) {
      World w = World::from_json(clump_scene(spheres, solver, R"("blocks": [{"min": [0, 0.2, 0], "max": [0.08, 0.28, 0.08]}])"));
      const StateArray x = w.array("particle.position");
      const ClumpCheck start = check(x, spheres);
      ASSERT_EQ(x.count % spheres, 0);
      while (w.time() < 1 - 1e-9) w.step();
      const ClumpCheck end = check(x, spheres);
      std::printf("%d-sphere clumps (%ld), %s: at the start distance error %.2e m, overlap %.2e m; after 1 s %.3e m, %.3e m\n",
                  spheres, x.count / spheres, solver.c_str(), start.distance_error, start.overlap, end.distance_error,
                  end.overlap);
      EXPECT_LT(start.distance_error, 1e-12) << spheres;
      EXPECT_LT(start.overlap, 0) << spheres;
      EXPECT_LT(end.distance_error, (solver == "xpbd" ? 0.005 : 0.03) * kRadius) << spheres << solver;
      EXPECT_LT(end.overlap, 0.05 * kRadius) << spheres << solver;
    }
  }
}

// Without rolling resistance nothing stops a sphere rolling on the ground, and a column of
// spheres (r = 4 mm, mu = 0.5, mu_r = 0; 10 cm wide, 15 cm tall) spreads flat as its grains roll
// away: after 2 s its top is below 2 cm (measured 1.0 cm) and its runout beyond 1 m (1.18 m).
// Pairs and triangles of the same spheres do not roll (their spheres carry no spin, and friction
// acts at their centres), and the same column leaves a pile: top above 5 cm (measured 8.6 and
// 7.3 cm), runout within 0.2 m (0.083 and 0.096 m). With 4 iterations that pile still creeps
// (scenes/granular_clumps.json): this compares the two at one time, 2 s.
TEST(GranularClumps, ClumpsPileWhereSpheresRollAway) {
  auto collapse = [](const std::string& clump) {
    World w = World::from_json(fmt::format(R"({{"name": "column", "settings": {{"dt": 0.005, "substeps": 10, "iterations": 4,
        "duration": 2}}, "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.5}},
        {{"name": "sand", "kind": "granular", "cylinders": [{{"base": [0, 0, 0], "radius": 0.05, "height": 0.15}}],
          "radius": 0.004, "friction": 0.5, "rolling_resistance": 0{}}}],
        "probes": [{{"name": "top", "type": "extent", "object": "sand", "axis": "y", "quantity": "max"}},
                   {{"name": "runout", "type": "runout", "object": "sand", "center": [0, 0, 0]}}]}})", clump));
    while (w.time() < 2 - 1e-9) w.step();
    return std::pair{w.probe_values()[0], w.probe_values()[1]};
  };
  const auto [sphere_top, sphere_runout] = collapse("");
  std::printf("column of spheres, mu_r = 0: top %.4f m, runout %.3f m\n", sphere_top, sphere_runout);
  EXPECT_LT(sphere_top, 0.02);
  EXPECT_GT(sphere_runout, 1.0);
  for (int spheres : {2, 3}) {
    const auto [top, runout] = collapse(fmt::format(R"(, "clump": {{"spheres": {}}})", spheres));
    std::printf("column of %d-sphere clumps, mu_r = 0: top %.4f m, runout %.3f m\n", spheres, top, runout);
    EXPECT_GT(top, 0.05) << spheres;
    EXPECT_LT(runout, 0.2) << spheres;
  }
}

// A lone pair spinning end over end at 10 rad/s in free space keeps its angular momentum and its
// length under both formulations: under nmd its cluster's fit turns with it although a line has
// no inertia about its own axis (shape_match_rows.hpp takes K's pseudo-inverse there). Tolerances:
// under nmd 1e-9 of the momentum (rounding); under xpbd 2 % (its position-level velocity keeps
// 1 - D^2 of a spin per substep, D = omega h = 2.5e-3: 1.2 % over 2,000 substeps); 1e-3 of r for
// the length.
TEST(GranularClumps, ASpinningPairKeepsSpinning) {
  for (const std::string solver : {"xpbd", "nmd"}) {
    World w = World::from_json(fmt::format(R"({{"name": "pair", "settings": {{"solver": "{}", "dt": 0.001, "substeps": 4,
        "duration": 1, "gravity": [0, 0, 0]}}, "objects": [{{"name": "sand", "kind": "granular",
        "blocks": [{{"min": [0, 0, 0], "max": [0.0153, 0.0153, 0.0153]}}], "radius": 0.005, "clump": {{"spheres": 2}}}}]}})",
                                           solver));
    StateArray x = w.array("particle.position"), v = w.array("particle.velocity");
    ASSERT_EQ(x.count, 2);
    const Vec3 c = 0.5 * (at(x, 0) + at(x, 1)), axis = (at(x, 1) - at(x, 0)).normalized();
    const Vec3 omega = 10 * axis.cross(Vec3(0.3, 1, 0.2)).normalized();  // across the pair
    for (long p = 0; p < 2; ++p) {
      const Vec3 u = omega.cross(at(x, p) - c);
      for (int k = 0; k < 3; ++k) v.values[3 * p + k] = u[k];
    }
    auto momentum = [&] {
      const Vec3 center = 0.5 * (at(x, 0) + at(x, 1));
      return Vec3((at(x, 0) - center).cross(at(v, 0)) + (at(x, 1) - center).cross(at(v, 1)));
    };
    const Vec3 L0 = momentum();
    while (w.time() < 0.5 - 1e-9) w.step();
    const Vec3 L1 = momentum();
    const Real length = (at(x, 1) - at(x, 0)).norm();
    std::printf("spinning pair (%s): angular momentum x %.10f, turned %.2e rad; length %.6e m (r)\n", solver.c_str(),
                L1.norm() / L0.norm(), L1.normalized().cross(L0.normalized()).norm(), length);
    EXPECT_NEAR(L1.norm() / L0.norm(), 1, solver == "nmd" ? 1e-9 : 2e-2) << solver;
    EXPECT_NEAR(length, kRadius, 1e-3 * kRadius) << solver;
  }
}

// A layer of 25 pairs dropped 1 cm onto the ground settles and falls asleep whole (every sphere
// asleep within 2 s, with the default sleep speed of 1 cm/s held for 0.5 s), and stays asleep to
// 4 s under both formulations: a sleeping clump is not fitted again (its shape-matching cluster is
// skipped), which would move its spheres and wake it.
TEST(GranularClumps, ASettledLayerOfClumpsSleeps) {
  for (const std::string solver : {"xpbd", "nmd"}) {
    World w = World::from_json(fmt::format(R"({{"name": "layer", "settings": {{"solver": "{}", "dt": 0.005, "substeps": 10,
        "iterations": 4, "duration": 4, "sleep": {{}}}}, "objects": [{{"name": "ground", "kind": "collider",
        "shape": {{"type": "plane"}}, "friction": 0.5}}, {{"name": "gravel", "kind": "granular",
        "blocks": [{{"min": [0, 0.01, 0], "max": [0.0765, 0.0253, 0.0765]}}], "radius": 0.005, "rolling_resistance": 0,
        "clump": {{"spheres": 2}}}}], "probes": [{{"name": "asleep", "type": "asleep", "object": "gravel"}}]}})",
                                           solver));
    const long spheres = w.objects().at(1).count;
    ASSERT_EQ(spheres, 50);
    Real first_all_asleep = -1, fewest_after = spheres;
    while (w.time() < 4 - 1e-9) {
      w.step();
      const Real asleep = w.probe_values()[0];
      if (first_all_asleep < 0 && asleep == spheres) first_all_asleep = w.time();
      if (first_all_asleep >= 0) fewest_after = std::min<Real>(fewest_after, asleep);
    }
    std::printf("layer of 25 pairs (%s): all asleep at %.3f s; fewest asleep after that %g of %ld\n", solver.c_str(),
                first_all_asleep, fewest_after, spheres);
    EXPECT_GE(first_all_asleep, 0) << solver;
    EXPECT_LE(first_all_asleep, 2) << solver;
    EXPECT_EQ(fewest_after, spheres) << solver;
  }
}

// Bad clump keys fail with their path.
TEST(GranularClumps, ClumpKeysAreChecked) {
  auto error = [](const std::string& clump, const std::string& extra = "") {
    try {
      World::from_json(fmt::format(R"({{"name": "bad", "settings": {{"dt": 0.001, "duration": 1}},
          "objects": [{{"name": "sand", "kind": "granular", "radius": 0.005, "clump": {}{}}}]}})", clump, extra));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string block = R"(, "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}])";
  EXPECT_NE(error(R"({"spheres": 5})", block).find("objects[0].clump.spheres"), std::string::npos);
  EXPECT_NE(error(R"({"spheres": 2, "spacing": 2})", block).find("objects[0].clump.spacing"), std::string::npos);
  EXPECT_NE(error(R"({"spheres": 2})", R"(, "emitter": {"shape": "disc", "center": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.03, "speed": 1})")
                .find("objects[0].emitter"), std::string::npos);
  EXPECT_EQ(error(R"({"spheres": 3, "spacing": 1.5})", block), "no error");
}

}  // namespace
}  // namespace moreau
