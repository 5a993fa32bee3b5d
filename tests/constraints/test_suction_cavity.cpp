// The suction cavity's volume and its derivatives (constraints/suction_cavity.hpp) against exact
// volumes and central differences.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "moreau/constraints/suction_cavity.hpp"

namespace moreau {
namespace {

// A lopsided pyramid cap over the square mouth [-1, 1]^2 in the plane y = 0: apex (0.3, 0.8, -0.2),
// four faces oriented into the cavity (down), the square's corners its rim.
struct Cap {
  SuctionCup cup;
  std::vector<Vec3> x;
  Cap() {
    x = {Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(-1, 0, 1), Vec3(0.3, 0.8, -0.2)};
    cup.cavity = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};  // (x1 - x0) x (x2 - x0) points down, into the cavity
    cup.cavity_vertices = {0, 1, 2, 3, 4};
    cup.rim = {0, 1, 2, 3};
  }
};

TEST(SuctionCavity, VolumeAndAreaOfAPyramidCapAreExact) {
  // A pyramid of base 4 m^2 and height 0.8 m holds 4 * 0.8 / 3 m^3 over the plane, whatever the apex's
  // sideways offset; the footprint is the base.
  const Cap cap;
  const CavityVolume v = cavity_volume(cap.cup, cap.x.data(), Vec3::Zero(), Vec3::UnitY());
  EXPECT_NEAR(v.volume, 4 * 0.8 / 3, 1e-14);
  EXPECT_NEAR(v.area, 4, 1e-14);
}

TEST(SuctionCavity, GradientsMatchCentralDifferences) {
  // Against a tilted plane (so every term of the formulas is non-zero), the derivatives by the
  // vertices, by translating the plane and by turning it about a body centre c. Step 1e-6 m (rad):
  // central differences of a cubic polynomial in the step err by ~1e-12; tolerance 1e-8.
  const Cap cap;
  const Vec3 o(0.1, -0.05, 0.02), n = Vec3(0.1, 1, -0.05).normalized(), c(0.4, -0.3, 0.25);
  const CavityVolume v = cavity_volume(cap.cup, cap.x.data(), o, n, c);
  const Real step = 1e-6;
  auto volume = [&](const std::vector<Vec3>& x, const Vec3& oo, const Vec3& nn) {
    return cavity_volume(cap.cup, x.data(), oo, nn, c).volume;
  };
  for (size_t k = 0; k < cap.x.size(); ++k)
    for (int a = 0; a < 3; ++a) {
      std::vector<Vec3> plus = cap.x, minus = cap.x;
      plus[k][a] += step;
      minus[k][a] -= step;
      EXPECT_NEAR(v.gradient[k][a], (volume(plus, o, n) - volume(minus, o, n)) / (2 * step), 1e-8)
          << "vertex " << k << " axis " << a;
    }
  for (int a = 0; a < 3; ++a) {
    const Vec3 e = Vec3::Unit(a);
    // Moving the surface by u changes V by -A (n . u).
    EXPECT_NEAR(-v.area * n[a], (volume(cap.x, o + step * e, n) - volume(cap.x, o - step * e, n)) / (2 * step), 1e-8);
    // Turning it by dtheta about c carries o to c + R (o - c) and n to R n.
    const Mat3 plus = Eigen::AngleAxis<Real>(step, e).toRotationMatrix();
    const Mat3 minus = Eigen::AngleAxis<Real>(-step, e).toRotationMatrix();
    const Real turned = (volume(cap.x, c + plus * (o - c), plus * n) - volume(cap.x, c + minus * (o - c), minus * n)) /
                        (2 * step);
    EXPECT_NEAR(v.surface_turn[a], turned, 1e-8) << "axis " << a;
  }
}

}  // namespace
}  // namespace moreau
