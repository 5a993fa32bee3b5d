// Position Based Fluids: kernel, density constraint, tank, determinism (issue 3).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <numeric>

#include "moreau/fluids/density_constraint.hpp"
#include "moreau/fluids/fluid_neighbors.hpp"
#include "moreau/fluids/fluid_velocity.hpp"
#include "moreau/fluids/pair_chunks.hpp"
#include "moreau/io/probes.hpp"
#include "moreau/model/diagnostics.hpp"
#include "dam_break_check.hpp"
#include "fluid_tank_checks.hpp"
#include "fluid_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

// Sum over a cubic lattice of spacing d around a particle: sum_j V W(x_i - x_j), V = d^3.
Real lattice_kernel_sum(const CubicSplineKernel& kernel, Real d) {
  Real sum = 0;
  const int reach = static_cast<int>(std::ceil(kernel.h / d));
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b)
      for (int c = -reach; c <= reach; ++c) sum += d * d * d * kernel.value(d * Vec3(a, b, c).norm());
  return sum;
}

TEST(SphKernel, IntegratesToOne) {
  // Midpoint quadrature of W over its support sphere: exact normalisation to 1e-6.
  const CubicSplineKernel kernel(0.1);
  const int n = 400;
  const Real dr = kernel.h / n;
  Real integral = 0;
  for (int k = 0; k < n; ++k) {
    const Real r = (k + 0.5) * dr;
    integral += 4 * kPi * r * r * kernel.value(r) * dr;
  }
  EXPECT_NEAR(integral, 1.0, 1e-6);
}

TEST(SphKernel, LatticeSumIsOneWithinOnePercent) {
  // The discrete sum at the scene lattice (spacing 2r, h = 4r) is what the rest state sees.
  const Real r = 0.01;
  const Real sum = lattice_kernel_sum(CubicSplineKernel(4 * r), 2 * r);
  std::printf("lattice sum %.6f\n", sum);
  EXPECT_NEAR(sum, 1.0, 0.01);
}

TEST(SphKernel, GradientMatchesFiniteDifference) {
  const CubicSplineKernel kernel(0.2);
  for (Real r : {0.01, 0.05, 0.099, 0.1, 0.101, 0.15, 0.19}) {
    const Real fd = (kernel.value(r + 1e-7) - kernel.value(r - 1e-7)) / 2e-7;
    EXPECT_NEAR(kernel.gradient_factor(r) * r, fd, 1e-5 * std::abs(kernel.value(0) / kernel.h)) << "r = " << r;
  }
}

TEST(SphKernel, SolverChunksMatchTheReferenceKernel) {
  // The pair loops use PairChunk's branch-free form; it must agree with the piecewise reference
  // to round-off (the r floor sqrt(r^2 + 1e-12 h^2) changes values by < 1e-11 relative here),
  // and pad lanes (beyond the last neighbour) must contribute exactly nothing.
  const CubicSplineKernel kernel(0.2);
  const std::vector<Real> distances{0.004, 0.05, 0.0999, 0.1, 0.1001, 0.15, 0.1999, 0.2, 0.25};
  std::vector<Vec3> x;
  for (Real r : distances) x.push_back(r * Vec3(1, 2, 2) / 3);
  const Index count = static_cast<Index>(x.size());
  // A neighbour row as FixedStrideLists keeps it: whole chunks, the last padded with valid indices.
  std::vector<Index> row((count + kPairChunk - 1) / kPairChunk * kPairChunk, 0);
  std::iota(row.begin(), row.begin() + count, 0);
  PairChunk chunk;
  for (Index begin = 0; begin < count; begin += kPairChunk) {
    chunk.load(Vec3::Zero(), x.data(), row.data(), begin, count, 2 * kernel.h);
    chunk.evaluate(kernel);
    for (int k = 0; k < kPairChunk; ++k) {
      if (begin + k >= count) {
        EXPECT_EQ(chunk.w[k], 0.0);
        EXPECT_EQ(chunk.g[k], 0.0);
        continue;
      }
      const Real r = distances[begin + k];
      EXPECT_NEAR(chunk.w[k], kernel.value(r), 1e-11 * kernel.value(0)) << "r = " << r;
      EXPECT_NEAR(chunk.g[k], kernel.gradient_factor(r), 1e-10 * std::abs(kernel.gradient_factor(0.01))) << "r = " << r;
    }
  }
}


TEST(FluidTank, SettlesToRestDensityAndHeightWithHydrostaticPressure) {
  Scene scene = scene_from_json(test::resting_tank_scene(R"({"dt": 0.002, "substeps": 2, "iterations": 2})"));
  const FluidState& f = scene.state.fluid;
  const Real r = 0.00625;
  const int columns = 12;
  ASSERT_EQ(f.count, columns * columns * 16);
  run_steps(scene, 500);  // 1 s: the initial settling has died out

  // Pressure p = rho g (H - y) (hydrostatics), over 250 more steps (0.5 s).
  const auto [slope, r2, surface] = test::fit_tank_pressure(scene, 250);
  std::printf("pressure gradient %.1f Pa/m (rho g = 9810), R^2 = %.5f, p = 0 at y = %.4f m\n", -slope, r2, surface);
  // Tolerances: the cubic-spline lattice gradient is consistent to 2 % (sum_j V r_ij (x) grad W_ij
  // = -1.02 I); the settled particle arrangement adds a bias of a few per cent that depends on the
  // last bits of the arithmetic (measured 9,717 ... 10,239 Pa/m across builds with and without
  // FMA and vector kernels, R^2 > 0.999 always), so the bound is 6 %.
  EXPECT_NEAR(-slope, 9810, 0.06 * 9810);
  EXPECT_GT(r2, 0.995);
  // Where the fitted pressure vanishes is the hydrostatic free surface: the same 2 % as the height
  // (measured 0.198-0.201 m; the top layer carries no pressure, the unilateral clamp).
  EXPECT_NEAR(surface, 0.2, 0.02 * 0.2);

  // Density: mean compression error below 1 % (issue 3), from the last density evaluation.
  Real mean_error = 0;
  for (Index i = 0; i < f.count; ++i) mean_error += std::max(f.density[i] / 1000 - 1, 0.0);
  mean_error /= f.count;
  // Height: the median over the lattice columns of the highest particle top.
  const Real height = test::median_column_top(f, 0.075, r);
  std::printf("mean density error %.4f, height %.4f m\n", mean_error, height);
  EXPECT_LT(mean_error, 0.01);
  EXPECT_NEAR(height, 0.2, 0.02 * 0.2);
  for (Index i = 0; i < f.count; ++i) ASSERT_LE(std::abs(f.position[i].x()), 0.075 - r + 1e-12) << "a particle left the tank";
}


// Water released from one side of a closed box: it surges, hits the far wall and sloshes.
const char* kSloshScene = R"({"name": "slosh", "settings": {"dt": 0.004, "substeps": 2, "iterations": 2},
  "objects": [
    {"name": "box", "kind": "collider", "inside": true,
     "shape": {"type": "box", "center": [0, 0.15, 0], "half_extents": [0.25, 0.15, 0.075]}},
    {"name": "water", "kind": "fluid", "particle_radius": 0.0125,
     "block": {"min": [-0.25, 0, -0.075], "max": [-0.1, 0.2, 0.075]}}]})";

Real total_energy(const Scene& s) { return kinetic_energy(s.model, s.state, -1) + potential_energy(s.model, s.state, -1); }

TEST(FluidSlosh, ClosedBoxKeepsEveryParticleAndDissipatesEnergy) {
  Scene scene = scene_from_json(kSloshScene);
  const FluidState& f = scene.state.fluid;
  const Index count = f.count;
  const Real e0 = total_energy(scene);
  Real reach = -1, e_max = e0;
  for (int s = 0; s < 1250; ++s) {  // 5 s
    run_steps(scene, 1);
    for (Index i = 0; i < f.count; ++i) reach = std::max(reach, f.position[i].x());
    e_max = std::max(e_max, total_energy(scene));
  }
  EXPECT_EQ(f.count, count);
  Index outside = 0;
  for (Index i = 0; i < f.count; ++i) {
    const Vec3& x = f.position[i];
    // The walls keep centres r inside; allow round-off.
    if (std::abs(x.x()) > 0.25 - 0.0125 + 1e-9 || x.y() < 0.0125 - 1e-9 || x.y() > 0.3 - 0.0125 + 1e-9 ||
        std::abs(x.z()) > 0.075 - 0.0125 + 1e-9) std::printf("%g %g %g\n", x.x(), x.y(), x.z());
    outside += std::abs(x.x()) > 0.25 - 0.0125 + 1e-9 || x.y() < 0.0125 - 1e-9 || x.y() > 0.3 - 0.0125 + 1e-9 ||
               std::abs(x.z()) > 0.075 - 0.0125 + 1e-9;
  }
  EXPECT_EQ(outside, 0);
  EXPECT_GT(reach, 0.2) << "the surge should reach the far wall";
  // Energy: no source in the scene, so the total (kinetic + potential) must not grow; the solver's
  // and XSPH's dissipation make it fall. The bound allows 1 % of the initial total energy for
  // round-off in the energy sums (measured: the maximum is the initial value itself).
  const Real e_end = total_energy(scene);
  std::printf("energy: start %.3f J, max %.3f J, end %.3f J\n", e0, e_max, e_end);
  EXPECT_LE(e_max, e0 + 0.01 * std::abs(e0));
  EXPECT_LT(e_end, e0);
}

TEST(FluidDeterminism, BitIdenticalForOneAndTwoThreads) {
  auto run = [](int threads) {
    Scene scene = scene_from_json(kSloshScene, {fmt::format("settings.threads={}", threads)});
    run_steps(scene, 100);
    return test::by_particle_id(scene.state.fluid, scene.state.fluid.position);
  };
  const auto one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k].second, two[k].second) << "particle " << one[k].first;
}

TEST(FluidConservation, CollidingBlobsKeepLinearAndAngularMomentum) {
  // Two blobs in free space (no gravity, no walls) collide off-centre at 2 m/s: the density
  // constraints push them apart and set them spinning. Every correction (density multipliers,
  // s_corr, viscosity) is a pair term m_i dx_i = -m_j dx_j parallel to x_i - x_j, so linear and
  // angular momentum are conserved. Angular momentum only up to the substep's O(h) lever-arm
  // error: a correction computed at the predicted positions x* is applied as velocity (x - x_s)/h,
  // whose moment about x_s differs by h v_ij x dx. XSPH is off: it smooths velocity differences
  // along W_ij rather than along x_ij and damps rotation, so it does not conserve angular momentum.
  // The blobs' viscosities (1 and 4 Pa s at 1000 and 800 kg/m^3: kinematic 1e-3 and 5e-3 m^2/s,
  // explicit) differ, so where they meet the pairs take the harmonic mean (interface_viscosity.hpp).
  Scene scene = scene_from_json(test::colliding_blobs_scene(1, 4));
  const Vec3 p0 = linear_momentum(scene.model, scene.state, -1);
  const Vec3 L0 = angular_momentum(scene.model, scene.state, -1, Vec3::Zero());
  const Real scale = 2 * 0.2 * std::abs(p0.x()) + kinetic_energy(scene.model, scene.state, -1);  // |m v| x lever arm
  Real max_pressure = 0;  // Pa, > 0 once a density constraint pushed
  for (int s = 0; s < 100; ++s) {
    run_steps(scene, 1);
    for (Index i = 0; i < scene.state.fluid.count; ++i) max_pressure = std::max(max_pressure, scene.state.fluid.pressure[i]);
  }
  ASSERT_GT(max_pressure, 0) << "the blobs never compressed each other";
  const Vec3 p1 = linear_momentum(scene.model, scene.state, -1);
  const Vec3 L1 = angular_momentum(scene.model, scene.state, -1, Vec3::Zero());
  const Real m_total = scene.state.fluid.count * 1000 * 8e-6;
  std::printf("|p1 - p0| = %.3g kg m/s; |L1 - L0| = %.3g kg m^2/s (scale %.3g)\n", (p1 - p0).norm(), (L1 - L0).norm(), scale);
  // Linear: round-off (measured 9e-14 kg m/s on 2.8 kg). Angular: measured 1.4e-4 (8.1e-5 of the
  // scale) with 4 substeps, the O(h) error above (with one viscosity for both blobs it was 1.1e-4,
  // and 3.2e-5 with 16 substeps); the bound leaves 12x margin.
  EXPECT_LT((p1 - p0).norm(), 1e-12 * m_total);
  EXPECT_LT((L1 - L0).norm(), 1e-3 * scale);
}

TEST(FluidVorticity, RigidRotationHasCurlTwiceTheAngularVelocity) {
  // v = Omega x x with Omega = (0, 0, 3) rad/s: curl v = (0, 0, 6) 1/s. Checked at an interior
  // particle of a lattice (the SPH curl is exact for linear fields up to the lattice consistency
  // of the kernel gradient, 2 %).
  Scene scene = scene_from_json(R"({"name": "spin", "settings": {"gravity": [0, 0, 0]},
    "objects": [{"name": "water", "kind": "fluid", "particle_radius": 0.01,
                 "block": {"min": [-0.1, -0.1, -0.1], "max": [0.1, 0.1, 0.1]}}]})");
  FluidState& f = scene.state.fluid;
  const Vec3 omega(0, 0, 3);
  for (Index i = 0; i < f.count; ++i) f.velocity[i] = omega.cross(f.position[i]);
  FluidScratch scratch;
  scratch.fit(scene.model.fluid);
#pragma omp parallel num_threads(1)
  update_fluid_neighbors(scene.model, f, scratch, 0);
  Index center = 0;
  for (Index i = 0; i < f.count; ++i)
    if (f.position[i].norm() < f.position[center].norm()) center = i;
  const Vec3 curl = fluid_vorticity(scene.model, f, center);
  EXPECT_NEAR(curl.z(), 6.0, 0.03 * 6.0);
  EXPECT_NEAR(curl.x(), 0.0, 1e-9);
  EXPECT_NEAR(curl.y(), 0.0, 1e-9);
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

TEST(FluidEmitter, ReleasesItsVolumeAndTheTankFillsToIt) {
  // A disc of radius 2 cm on the 1 cm lattice has 13 points (|(i, j)| <= 2); at 1 m/s a layer is
  // born every 10 ms, so by the stop time 0.8 s it has released 81 layers = 1,053 particles, each
  // carrying (2r)^3 = 1e-6 m^3: 1.053e-3 m^3, a 26.3 mm layer in the 0.2 x 0.2 m tank.
  Scene scene = test::scene_from_json(R"({"name": "pour", "settings": {"dt": 0.004, "substeps": 4, "iterations": 2},
    "objects": [
      {"name": "tank", "kind": "collider", "inside": true,
       "shape": {"type": "box", "center": [0, 0.25, 0], "half_extents": [0.1, 0.25, 0.1]}},
      {"name": "water", "kind": "fluid", "particle_radius": 0.005,
       "emitter": {"shape": "disc", "center": [0, 0.3, 0], "direction": [0, -1, 0], "radius": 0.02,
                   "speed": 1.0, "stop": 0.8}}]})");
  const FluidState& f = scene.state.fluid;
  EXPECT_EQ(f.count, 0);
  EXPECT_EQ(scene.model.fluid.capacity, 1053);
  test::run_steps(scene, 100);  // steps start at 0 ... 0.396 s: layers born at 0, 0.01, ..., 0.39
  EXPECT_EQ(f.count, 40 * 13);
  test::run_steps(scene, 400);  // 2 s: all released, settled
  ASSERT_EQ(f.count, 1053);
  std::vector<Index> ids(f.id.begin(), f.id.begin() + f.count);
  std::sort(ids.begin(), ids.end());
  for (Index k = 0; k < f.count; ++k) ASSERT_EQ(ids[k], k) << "ids must be unique and dense";
  // Settled depth: the median column top, as in the resting tank; volume / area = 26.3 mm, and the
  // free surface sits about r/2 low (resting-tank test), so the tolerance is r = 5 mm.
  const Real r = 0.005, depth = test::median_column_top(f, 0.1, r);
  std::printf("settled depth %.4f m (volume / area = 0.0263 m)\n", depth);
  EXPECT_NEAR(depth, 1.053e-3 / 0.04, r);
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

TEST(FluidDamBreak, DepthProfileApproachesRittersShallowWaterSolution) {
  // Measured worst 10.3 mm, at x = -0.2 m, t = 0.55 s (2.6 mm there by 0.75 s); front 2.55 m/s.
  test::check_ritter_dam_break(R"({"dt": 0.002, "substeps": 2, "iterations": 2})");
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

// Radii of gyration (sqrt of the eigenvalues of the gyration tensor) of the live fluid particles,
// largest over smallest: sqrt((20^2 - 1) / (5^2 - 1)) = 4.077 for the 20 x 5 x 5 lattice block
// below, 1 for a sphere.
Real gyration_ratio(const FluidState& f) {
  Vec3 c = Vec3::Zero();
  for (Index i = 0; i < f.count; ++i) c += f.position[i];
  c /= f.count;
  Mat3 g = Mat3::Zero();
  for (Index i = 0; i < f.count; ++i) g += (f.position[i] - c) * (f.position[i] - c).transpose();
  const Vec3 eig = Eigen::SelfAdjointEigenSolver<Mat3>(g).eigenvalues();
  return std::sqrt(eig.maxCoeff() / eig.minCoeff());
}

Scene weightless_bar(Real surface_tension) {
  return test::scene_from_json(fmt::format(R"({{"name": "bar", "settings": {{"dt": 0.002, "substeps": 2, "iterations": 2, "gravity": [0, 0, 0]}},
    "objects": [{{"name": "water", "kind": "fluid", "particle_radius": 0.005, "xsph": 0.3, "surface_tension": {},
      "block": {{"min": [-0.1, -0.025, -0.025], "max": [0.1, 0.025, 0.025]}}}}]}})",
                                           surface_tension));
}

TEST(FluidSurfaceTension, WeightlessBarOfWaterPullsItselfIntoASphere) {
  // Zero gravity: a 0.2 x 0.05 x 0.05 m bar (500 particles) has nothing to change its shape but
  // surface tension, which minimises the surface: the bar must round up into a ball (gyration
  // ratio 4.08 -> 1), without surface tension it must keep its shape, and the pair forces are equal
  // and opposite, so the momentum stays zero. gamma = 2.5 N/m gives the ball of the bar's volume
  // (R = 4.9 cm) an l = 2 period of 0.5 s. Strong XSPH smoothing (0.3) damps the retraction: the
  // drop's own oscillation is lightly damped (ratio 0.06), and a bar of 4:1 overshoots into a
  // sloshing ball instead (ratio between 1.07 and 1.8 over 3 s, measured).
  Scene plain = weightless_bar(0), tense = weightless_bar(2.5);
  EXPECT_NEAR(gyration_ratio(tense.state.fluid), std::sqrt(399.0 / 24), 1e-9);
  run_steps(plain, 500);
  run_steps(tense, 500);  // 1 s
  const Real ratio_plain = gyration_ratio(plain.state.fluid), ratio_tense = gyration_ratio(tense.state.fluid);
  const Vec3 p = linear_momentum(tense.model, tense.state, -1);
  std::printf("gyration ratio after 1 s: %.3f without, %.3f with surface tension; momentum %.2e kg m/s\n", ratio_plain,
              ratio_tense, p.norm());
  EXPECT_GT(ratio_plain, 3.5);   // measured 3.99: the unilateral constraint only relaxes edges and corners
  EXPECT_LT(ratio_tense, 1.1);   // a ball (measured 1.018; 1.016-1.025 from 1 to 3 s)
  EXPECT_LT(p.norm(), 1e-12);    // round-off of 500 particles' sums (momentum scale 0.5 kg * 0.1 m/s)
}

// A fluid filled from a closed OBJ box holds the lattice of the same block. The OBJ reader keeps
// vertices in single precision: 0.06 reads as 0.0599999987, so the 0.12 m box is 14.9999997
// spacings of 8 mm wide, and the count used to lose a column on each side axis (4,900 particles
// for 5,625).
TEST(FluidSources, AClosedMeshFillsLikeTheBlockItBounds) {
  const std::string dir = test::temp_dir("fluid-mesh");
  {
    std::ofstream out(dir + "/box.obj");
    for (int i = 0; i < 8; ++i)
      out << fmt::format("v {} {} {}\n", (i & 1) ? 0.06 : -0.06, (i & 2) ? 0.2 : 0.0, (i & 4) ? 0.06 : -0.06);
    // Vertex i + 1 sits at the corner (i & 1, i & 2, i & 4); two triangles per face.
    out << "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  }
  auto particles = [&](const std::string& source) {
    const std::string path = dir + "/scene.json";
    std::ofstream(path) << fmt::format(R"({{"name": "fill", "settings": {{"dt": 0.001}},
        "objects": [{{"name": "water", "kind": "fluid", "particle_radius": 0.004, {}}}]}})", source);
    const Scene scene = load_scene(path);
    return std::vector<Vec3>(scene.state.fluid.position.begin(), scene.state.fluid.position.begin() + scene.state.fluid.count);
  };
  const std::vector<Vec3> from_mesh = particles(R"("mesh": "box.obj")");
  const std::vector<Vec3> from_block = particles(R"("block": {"min": [-0.06, 0, -0.06], "max": [0.06, 0.2, 0.06]})");
  ASSERT_EQ(from_block.size(), 15u * 25 * 15);
  ASSERT_EQ(from_mesh.size(), from_block.size());
  // The same points up to the single-precision box corners (lattice offsets below 1e-8 m).
  Real worst = 0;
  for (std::size_t k = 0; k < from_mesh.size(); ++k) worst = std::max(worst, (from_mesh[k] - from_block[k]).norm());
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace moreau
