// Rows of particle contacts (constraints/particle_contact_rows.hpp, particle_body_contact_rows.hpp)
// against the geometry they describe: the normal row's value is the overlap, the friction rows'
// values the slip since the substep began, the three directions are orthonormal, and the
// gradients are the derivatives of the values.
#include <gtest/gtest.h>

#include "moreau/constraints/particle_body_contact_rows.hpp"
#include "moreau/constraints/particle_contact_rows.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

// Values of order 0.1 m built from a few products: round-off is a few ulps (~1e-17 m each), so
// 1e-15 m holds any correct evaluation and fails a wrong sign or offset by orders of magnitude.
constexpr Real kExact = 1e-15;
// Central differences with step 1e-6 m: the truncation error is ~1e-12 per unit of curvature,
// far below 1e-8.
constexpr Real kStep = 1e-6, kDerivative = 1e-8;

void expect_orthonormal(const Eigen::Matrix<Real, 3, 3>& directions) {
  EXPECT_LT((directions * directions.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff(), kExact);
}

TEST(ParticleContactRows, PairRowsAreTheOverlapTheSlipAndTheirDerivatives) {
  // Two particles of radius 0.05 m, 0.08 m apart (0.02 m overlap) along a skew direction; both
  // slid since the substep began.
  std::array<Vec3, 2> x{Vec3(0.3, 0.2, -0.1), Vec3(0.3, 0.2, -0.1) - 0.08 * Vec3(1, 2, 2).normalized()};
  std::array<Vec3, 2> x_start{x[0] - Vec3(0.004, 0.001, -0.002), x[1] - Vec3(-0.001, 0.0, 0.003)};
  const auto rows = pair_contact_rows(0, 1, 0.1, 0.4, x.data(), x_start.data());
  EXPECT_NEAR(rows.C[0], -0.02, kExact);
  EXPECT_EQ(rows.static_friction, 0.4);
  EXPECT_EQ(rows.lower[0], 0);
  expect_orthonormal(rows.gradient[0]);
  EXPECT_EQ(rows.gradient[1], -rows.gradient[0]);
  const Vec3 n = rows.gradient[0].row(0).transpose();
  const Vec3 dp = (x[0] - x_start[0]) - (x[1] - x_start[1]);
  const Vec3 slip = rows.C[1] * rows.gradient[0].row(1).transpose() + rows.C[2] * rows.gradient[0].row(2).transpose();
  EXPECT_LT((slip - (dp - dp.dot(n) * n)).norm(), kExact);

  // Derivatives at x = x_start, where the slip rows' directions do not turn to first order in
  // their values (the values are zero), so every row's gradient is exact.
  std::array<Vec3, 2> at_rest = x;
  const auto still = pair_contact_rows(0, 1, 0.1, 0.4, at_rest.data(), at_rest.data());
  for (int e = 0; e < 2; ++e)
    for (int k = 0; k < 3; ++k) {
      std::array<Vec3, 2> plus = x, minus = x;
      plus[e](k) += kStep;
      minus[e](k) -= kStep;
      const auto p = pair_contact_rows(0, 1, 0.1, 0.4, plus.data(), at_rest.data());
      const auto m = pair_contact_rows(0, 1, 0.1, 0.4, minus.data(), at_rest.data());
      for (int r = 0; r < 3; ++r)
        EXPECT_NEAR((p.C[r] - m.C[r]) / (2 * kStep), still.gradient[e](r, k), kDerivative)
            << "end " << e << " row " << r << " coordinate " << k;
    }
}

TEST(ParticleContactRows, CoincidentCentresHaveNoDirection) {
  std::array<Vec3, 2> x{Vec3(1, 2, 3), Vec3(1, 2, 3)};
  const auto rows = pair_contact_rows(0, 1, 0.1, 0.4, x.data(), x.data());
  EXPECT_EQ(rows.C[0], -0.1);
  EXPECT_TRUE(rows.gradient[0].isZero());
  EXPECT_TRUE(rows.gradient[1].isZero());
}

TEST(ParticleContactRows, ColliderRowsMeasureTheSlipAgainstAMovingCollider) {
  // A particle 3 mm into a floor (gap 0.01 m, so C = -0.013 m) that moved 5 mm along x while the
  // floor moved 2 mm: the slip is 3 mm along x.
  const Vec3 n = Vec3::UnitY();
  std::array<Vec3, 1> x{Vec3(0.2, -0.003, 0.1)}, x_start{Vec3(0.195, 0.001, 0.1)};
  const auto rows = collider_contact_rows(0, x[0].y(), n, 0.01, 0.7, Vec3(0.002, 0, 0), x.data(), x_start.data());
  EXPECT_NEAR(rows.C[0], -0.013, kExact);
  EXPECT_EQ(rows.static_friction, 0.7);
  expect_orthonormal(rows.gradient[0]);
  EXPECT_EQ(Vec3(rows.gradient[0].row(0).transpose()), n);
  const Vec3 slip = rows.C[1] * rows.gradient[0].row(1).transpose() + rows.C[2] * rows.gradient[0].row(2).transpose();
  EXPECT_LT((slip - Vec3(0.003, 0, 0)).norm(), kExact);
}

TEST(ParticleContactRows, ParticleBodyRowsAreThePenetrationIntoATurnedBoxAndItsDerivatives) {
  // One cloth particle (collider gap = its radius) pushed 4 mm into the top face of a turned box.
  Scene s = test::scene_from_json(R"({"name": "rows", "settings": {"gravity": [0, 0, 0]}, "objects": [
      {"name": "box", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.2, 0.1, 0.15]},
       "position": [0, 0, 0], "density": 100, "friction": 0.6},
      {"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [0.1, 0.1], "resolution": [2, 2],
       "center": [0, 0.5, 0]}, "material": {"area_density": 0.1}}]})");
  const Model& model = s.model;
  State& state = s.state;
  const Index box = model.objects[model.find_object("box")].body, p = 0;
  state.rigid.orientation[box] = Quat(Eigen::AngleAxis<Real>(0.2, Vec3(0, 0, 1)));
  state.rigid.position[box] = Vec3(0.01, -0.02, 0.03);
  const Real gap = model.particle_collider_gap[p];
  const Vec3 top = state.rigid.position[box] + state.rigid.orientation[box] * Vec3(0.05, 0.1, 0.02);
  const Vec3 up = state.rigid.orientation[box] * Vec3::UnitY();
  state.position[p] = top + (gap - 0.004) * up;
  const std::vector<Vec3> x_start = state.position;
  const SubstepStart start{x_start.data(), state.rigid.position.data(), state.rigid.orientation.data()};

  const ParticleBodyContactRows result = particle_body_rows(model, state, start, box, p, 0.6);
  const BodyRows& rows = result.rows;
  ASSERT_EQ(rows.size(), 3);
  EXPECT_NEAR(rows.C[0], -0.004, kExact);
  EXPECT_EQ(rows.lower[0], 0);
  EXPECT_EQ(result.static_friction, 0.6);
  EXPECT_NEAR(rows.C[1], 0, kExact);
  EXPECT_NEAR(rows.C[2], 0, kExact);
  EXPECT_LT((Vec3(rows.jacobian[0].block<1, 3>(0, 0).transpose()) - up).norm(), kExact);

  // Central differences over the particle's position and the box's position and rotation vector.
  for (int e = 0; e < 2; ++e)
    for (int k = 0; k < (e == 0 ? 3 : 6); ++k) {
      auto moved = [&](Real sign) {
        State t = state;
        const Vec3 d = sign * kStep * Vec3::Unit(k % 3);
        if (e == 0) t.position[p] += d;
        else if (k < 3) t.rigid.position[box] += d;
        else t.rigid.orientation[box] = Quat(Eigen::AngleAxis<Real>(sign * kStep, Vec3::Unit(k % 3))) * t.rigid.orientation[box];
        return particle_body_rows(model, t, start, box, p, 0.6).rows;
      };
      const BodyRows plus = moved(1), minus = moved(-1);
      for (int r = 0; r < 3; ++r)
        EXPECT_NEAR((plus.C[r] - minus.C[r]) / (2 * kStep), rows.jacobian[e](r, k), kDerivative)
            << "end " << e << " row " << r << " coordinate " << k;
    }
}

}  // namespace
}  // namespace moreau
