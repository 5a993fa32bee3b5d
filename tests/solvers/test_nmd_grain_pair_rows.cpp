// A grain pair's rows in closed form (nmd_system.hpp, GrainPairRows) are the same rows as the
// turning contact built entry by entry (turning_contact_rows.hpp): for two unequal grains, whose
// friction and turning rows couple, both give the same right-hand sides, diagonals and bounds, and
// the same impulses and velocities after one and after thirty projected Gauss-Seidel sweeps, with
// the friction and the rolling resistance at their bounds or within them. The two differ only in
// the order of their additions: 1e-12 relative on the system and the impulses, 1e-11 on the
// velocities, which sum thirty sweeps' changes onto spins of tens of rad/s.
#include <gtest/gtest.h>

#include <random>

#include "moreau/constraints/contact_rows.hpp"
#include "moreau/solvers/nmd/projected_gauss_seidel.hpp"
#include "moreau/solvers/nmd/turning_contact_rows.hpp"

namespace moreau {
namespace {

constexpr Real kStep = 1e-3;  // s

struct Pair {
  Vec3 n, t1, t2;
  Real arm[2];
  Real gap;         // m: C of the normal row
  Real friction;    // mu
  Real rolling;     // m: mu_r R*
};

// Two grains (masses 2 and 3 g, radii 5 and 7 mm) with random velocities and spins.
VelocitySpace two_grains(std::mt19937& rng) {
  std::uniform_real_distribution<Real> speed(-1, 1);
  VelocitySpace space;
  space.particles = 2;
  space.spins = 2;
  space.particle_inv_mass = {1 / 0.002, 1 / 0.003};
  space.spin_inv_inertia = {5 / (2 * 0.002 * 0.005 * 0.005), 5 / (2 * 0.003 * 0.007 * 0.007)};
  space.v.resize(12);
  for (Real& value : space.v) value = speed(rng);
  for (int c = 6; c < 12; ++c) space.v[c] *= 100;  // spins of tens of rad/s
  return space;
}

// The fields every contact input shares: a penetrating normal row of compliance 1e-7 m/N, friction
// rows of static and kinetic mu, turning rows bounded by the rolling resistance.
void set_contact_fields(NmdBlockInput& in, const Pair& p) {
  in.C.setZero();
  in.C[0] = p.gap;
  in.level[1] = in.level[2] = RowLevel::friction;
  in.lower[0] = 0;
  in.compliance(0, 0) = 1e-7;
  in.static_friction = in.dynamic_friction = p.friction;
}

NmdBlockInput entry_by_entry(const VelocitySpace& space, const Pair& p) {
  NmdBlockInput in;
  in.resize(3, 2);
  in.end = {space.particle_end(0), space.particle_end(1)};
  const Vec3 direction[3] = {p.n, p.t1, p.t2};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      in.at(r, 0)[c] = direction[r][c];
      in.at(r, 1)[c] = -direction[r][c];
    }
  in.kind = NmdBlockKind::contact;
  set_contact_fields(in, p);
  EXPECT_TRUE(add_turning_rows(in, space, {TurningSide{0, p.arm[0]}, TurningSide{1, p.arm[1]}}, p.n, p.t1, p.t2,
                               p.rolling));
  return in;
}

NmdBlockInput closed_form(const VelocitySpace& space, const Pair& p) {
  NmdBlockInput in;
  in.resize(6, 4, false);
  in.end = {space.particle_end(0), space.particle_end(1), space.spin_end(0), space.spin_end(1)};
  in.kind = NmdBlockKind::grain_pair;
  set_contact_fields(in, p);
  for (int r = 3; r < 6; ++r) in.level[r] = RowLevel::friction;
  in.rolling = p.rolling;
  in.grain_pair.n = p.n;
  in.grain_pair.t1 = p.t1;
  in.grain_pair.t2 = p.t2;
  in.grain_pair.arm[0] = p.arm[0];
  in.grain_pair.arm[1] = p.arm[1];
  return in;
}

// Solves one block by `sweeps` sweeps from zero impulses; returns the system and the velocities.
std::pair<NmdSystem, VelocitySpace> solve(const NmdBlockInput& in, VelocitySpace space, int sweeps) {
  NmdSettings settings;
  settings.iterations = sweeps;
  settings.warm_start = false;
  NmdSystem system;
  system.add(in, space, kStep, settings);
  SweepSchedule schedule;
  schedule.build(system, static_cast<Index>(space.v.size()));
  projected_gauss_seidel(system, space, settings, schedule, 1);
  return {system, space};
}

TEST(NmdGrainPairRows, ClosedFormRowsSolveAsTheRowsBuiltEntryByEntry) {
  std::mt19937 rng(7);
  std::normal_distribution<Real> gauss;
  int saturated_friction = 0, saturated_rolling = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const VelocitySpace space = two_grains(rng);
    Pair p;
    p.n = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    p.t1 = contact_tangent(p.n);
    p.t2 = p.n.cross(p.t1);
    p.gap = -1e-4 * (trial % 5);
    p.arm[0] = 0.005 * (1 + p.gap / 0.012);
    p.arm[1] = 0.007 * (1 + p.gap / 0.012);
    p.friction = trial % 2 ? 0.5 : 0.05;
    p.rolling = (trial % 3) * 0.2 * 0.005 * 0.007 / 0.012;
    for (int sweeps : {1, 30}) {
      const auto [a, va] = solve(entry_by_entry(space, p), space, sweeps);
      const auto [b, vb] = solve(closed_form(space, p), space, sweeps);
      ASSERT_EQ(a.row_count(), 6);
      ASSERT_EQ(b.row_count(), 6);
      EXPECT_EQ(a.blocks[0].friction, b.blocks[0].friction);
      for (Index r = 0; r < 6; ++r) {
        const Real scale = std::max(Real(1), std::abs(a.rhs[r]));
        EXPECT_NEAR(a.rhs[r], b.rhs[r], 1e-12 * scale) << "row " << r;
        EXPECT_NEAR(a.sigma[r], b.sigma[r], 1e-12 * std::abs(a.sigma[r]));
        EXPECT_NEAR(a.inverse_diagonal[r], b.inverse_diagonal[r], 1e-12 * a.inverse_diagonal[r]) << "row " << r;
        EXPECT_NEAR(a.impulse[r], b.impulse[r], 1e-12 * (std::abs(a.impulse[r]) + 1e-9)) << "row " << r;
      }
      for (size_t c = 0; c < va.v.size(); ++c) EXPECT_NEAR(va.v[c], vb.v[c], 1e-11 * (1 + std::abs(va.v[c])));
      if (sweeps == 30) {
        const Real normal = a.impulse[0];
        saturated_friction += std::hypot(a.impulse[1], a.impulse[2]) > (1 - 1e-9) * a.blocks[0].friction * normal;
        saturated_rolling += Vec3(a.impulse[3], a.impulse[4], a.impulse[5]).norm() > (1 - 1e-9) * p.rolling * normal;
      }
    }
  }
  std::printf("50 random grain pairs: friction at its bound in %d, rolling resistance in %d\n", saturated_friction,
              saturated_rolling);
  EXPECT_GT(saturated_friction, 5);  // the bounds were exercised
  EXPECT_GT(saturated_rolling, 5);
  EXPECT_LT(saturated_friction, 50);
}

}  // namespace
}  // namespace moreau
