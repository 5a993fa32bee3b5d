// Every constraint family: the analytic gradient against central finite differences.
// Tolerance: central differences with step 1e-6 on O(1) coordinates have truncation error
// ~1e-12 * |C'''| and round-off ~1e-16/1e-6 = 1e-10; 1e-6 absolute leaves a wide margin while any
// sign or index error (an O(1) mistake) fails.
#include <gtest/gtest.h>

#include <random>

#include "moreau/constraints/dihedral_bending.hpp"
#include "moreau/constraints/distance.hpp"
#include "moreau/constraints/neo_hookean_tet.hpp"
#include "moreau/constraints/tet_volume.hpp"
#include "moreau/constraints/triangle_strain.hpp"

using namespace moreau;

namespace {

constexpr Real kStep = 1e-6;
constexpr Real kTolerance = 1e-6;

std::vector<Vec3> random_points(int n, unsigned seed, Real jitter) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(-jitter, jitter);
  std::vector<Vec3> p(n);
  for (auto& x : p) x = Vec3(u(rng), u(rng), u(rng));
  return p;
}

// Central difference of f with respect to point i, coordinate d.
template <class F>
Real central_difference(std::vector<Vec3> x, int i, int d, F&& f) {
  x[i][d] += kStep;
  const Real plus = f(x);
  x[i][d] -= 2 * kStep;
  const Real minus = f(x);
  return (plus - minus) / (2 * kStep);
}

}  // namespace

TEST(ConstraintGradients, DistanceMatchesFiniteDifferences) {
  auto x = random_points(2, 1, 1.0);
  const auto v = evaluate_distance(x[0], x[1], 0.3);
  auto C = [](const std::vector<Vec3>& y) { return evaluate_distance(y[0], y[1], 0.3).C; };
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(v.grad0[d], central_difference(x, 0, d, C), kTolerance);
    EXPECT_NEAR(-v.grad0[d], central_difference(x, 1, d, C), kTolerance);
  }
}

TEST(ConstraintGradients, DihedralAngleMatchesFiniteDifferences) {
  // A bent hinge: edge along x, wings at about +-40 degrees, with random perturbations.
  for (unsigned seed = 1; seed <= 5; ++seed) {
    auto noise = random_points(4, seed, 0.1);
    std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.4, 0.6, -0.8), Vec3(0.6, 0.5, 0.9)};
    for (int i = 0; i < 4; ++i) x[i] += noise[i];
    const auto v = evaluate_dihedral(x[0], x[1], x[2], x[3]);
    auto theta = [](const std::vector<Vec3>& y) { return evaluate_dihedral(y[0], y[1], y[2], y[3]).theta; };
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(v.grad[i][d], central_difference(x, i, d, theta), kTolerance) << "vertex " << i;
  }
}

TEST(ConstraintGradients, DihedralAngleOfKnownHinge) {
  // Wings folded up symmetrically by 30 degrees each: the normals differ by 60 degrees.
  const Real a = 30 * kPi / 180;
  const Vec3 e0(0, 0, 0), e1(1, 0, 0);
  const Vec3 o0(0.5, std::sin(a), -std::cos(a)), o1(0.5, std::sin(a), std::cos(a));
  EXPECT_NEAR(std::abs(evaluate_dihedral(e0, e1, o0, o1).theta), 2 * a, 1e-12);
  EXPECT_NEAR(evaluate_dihedral(e0, e1, Vec3(0.5, 0, -1), Vec3(0.5, 0, 1)).theta, 0.0, 1e-15);
}

TEST(ConstraintGradients, TriangleStrainMatchesFiniteDifferences) {
  TriangleStrainConstraints c;
  const Vec3 X0(0, 0, 0), X1(1, 0.1, 0), X2(0.2, 0.9, 0.1);
  c.add({0, 1, 2}, X0, X1, X2, 1e5, 0.3, 1e-3, 0, 0);
  auto noise = random_points(3, 7, 0.2);
  std::vector<Vec3> x{X0 + noise[0], X1 + noise[1], X2 + noise[2]};
  const auto v = evaluate_triangle_strain(x[0], x[1], x[2], c.rest_inverse[0]);
  for (int r = 0; r < 3; ++r) {
    auto Cr = [&](const std::vector<Vec3>& y) { return evaluate_triangle_strain(y[0], y[1], y[2], c.rest_inverse[0]).C[r]; };
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(v.grad[i](r, d), central_difference(x, i, d, Cr), kTolerance);
  }
  // At rest the Green strain vanishes.
  EXPECT_LT(evaluate_triangle_strain(X0, X1, X2, c.rest_inverse[0]).C.norm(), 1e-14);
}

TEST(ConstraintGradients, NeoHookeanMatchesFiniteDifferences) {
  NeoHookeanTetConstraints c;
  const std::array<Vec3, 4> X{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  c.add({0, 1, 2, 3}, X, 1e5, 0.3, 0, 0);
  const NeoHookeanElement& e = c.elements[0];
  auto noise = random_points(4, 3, 0.2);
  std::vector<Vec3> x(4);
  for (int i = 0; i < 4; ++i) x[i] = X[i] + noise[i];
  // The same evaluation the projection uses.
  const auto v = evaluate_neo_hookean({x[0], x[1], x[2], x[3]}, e);
  auto CH = [&](const std::vector<Vec3>& y) { return evaluate_neo_hookean({y[0], y[1], y[2], y[3]}, e).C_H; };
  auto CD = [&](const std::vector<Vec3>& y) { return evaluate_neo_hookean({y[0], y[1], y[2], y[3]}, e).C_D; };
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d) {
      EXPECT_NEAR(v.grad_H[i][d], central_difference(x, i, d, CH), kTolerance);
      EXPECT_NEAR(v.grad_D[i][d], central_difference(x, i, d, CD), kTolerance);
    }
}

TEST(ConstraintGradients, TetVolumeMatchesFiniteDifferences) {
  TetVolumeConstraints c;
  const std::array<Vec3, 4> X{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  c.add({0, 1, 2, 3}, X, 1e-6, 0, 0);
  auto noise = random_points(4, 5, 0.2);
  std::vector<Vec3> x(4);
  for (int i = 0; i < 4; ++i) x[i] = X[i] + noise[i];
  const auto v = evaluate_tet_volume({x[0], x[1], x[2], x[3]}, c.rest_inverse[0]);
  auto C = [&](const std::vector<Vec3>& y) { return evaluate_tet_volume({y[0], y[1], y[2], y[3]}, c.rest_inverse[0]).C; };
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(v.grad[i][d], central_difference(x, i, d, C), kTolerance);
  // C = V/V0 - 1 against the signed volume formula.
  const Real V = tet_signed_volume(x[0], x[1], x[2], x[3]);
  EXPECT_NEAR(v.C, V / (1.0 / 6.0) - 1, 1e-13);
}
