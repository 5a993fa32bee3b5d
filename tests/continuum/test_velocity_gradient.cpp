// The Wendland kernel and the kernel-corrected velocity gradient (continuum/velocity_gradient.hpp):
// the kernel integrates to one and its gradient is its derivative; the corrected gradient is exact
// for linear velocity fields on irregular neighbourhoods, inside a block and at its corner, and
// within the plane of a flat neighbourhood.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "moreau/continuum/velocity_gradient.hpp"

namespace moreau {
namespace {

TEST(VelocityGradient, WendlandKernelIntegratesToOneAndItsGradientIsItsDerivative) {
  const WendlandKernel kernel(0.02);
  // Midpoint sum over a lattice of spacing h/40: the quadrature's error is O(spacing^2).
  const Real s = kernel.h / 40;
  Real integral = 0;
  for (int i = -40; i < 40; ++i)
    for (int j = -40; j < 40; ++j)
      for (int k = -40; k < 40; ++k) integral += s * s * s * kernel.value(s * Vec3(i + 0.5, j + 0.5, k + 0.5).norm());
  std::printf("Wendland kernel: integral %.8f\n", integral);
  EXPECT_NEAR(integral, 1, 1e-4);
  for (Real r = 0.001; r < 0.02; r += 0.0017) {
    const Real step = 1e-7, derivative = (kernel.value(r + step) - kernel.value(r - step)) / (2 * step);
    EXPECT_NEAR(kernel.gradient_factor(r) * r, derivative, 1e-6 * std::abs(derivative)) << r;
  }
  EXPECT_EQ(kernel.value(0.02), 0);
  EXPECT_EQ(kernel.gradient_factor(0.02), 0);
}

// A block of 8 x 8 x 8 particles at spacing r jittered by up to 0.2 r, kernel support 2 r.
struct Cloud {
  std::vector<Vec3> x;
  Real volume;
};

Cloud jittered_block(Real r, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> jitter(-0.2 * r, 0.2 * r);
  Cloud c{{}, r * r * r};
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 8; ++k) c.x.push_back(r * Vec3(i, j, k) + Vec3(jitter(rng), jitter(rng), jitter(rng)));
  return c;
}

// grad v at particle p of the cloud for v = A x + c, against A.
Real gradient_error(const std::vector<Vec3>& x, Real volume, const WendlandKernel& kernel, size_t p, const Mat3& A) {
  std::vector<KernelNeighbor> neighbors;
  std::vector<Vec3> dv;
  for (size_t b = 0; b < x.size(); ++b) {
    const Vec3 offset = x[b] - x[p];
    if (b == p || offset.norm() >= kernel.h) continue;
    neighbors.push_back({offset, volume});
    dv.push_back(A * offset);
  }
  const Mat3 L = kernel_correction(kernel, neighbors);
  return (velocity_gradient(kernel, L, neighbors, dv) - A).norm() / A.norm();
}

TEST(VelocityGradient, ExactForLinearFieldsInsideABlockAndAtItsCorner) {
  const Real r = 0.01;
  const WendlandKernel kernel(2 * r);
  std::mt19937 rng(29);
  std::normal_distribution<Real> g;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Cloud c = jittered_block(r, seed);
    Mat3 A;
    for (int i = 0; i < 9; ++i) A.data()[i] = g(rng);
    const size_t interior = (3 * 8 + 4) * 8 + 3, corner = 0;
    const Real inside = gradient_error(c.x, c.volume, kernel, interior, A);
    const Real at_corner = gradient_error(c.x, c.volume, kernel, corner, A);
    EXPECT_LT(inside, 1e-12);
    EXPECT_LT(at_corner, 1e-12);
  }
}

// Neighbours in the plane z = 0 only (a sheet one particle thick): M has rank 2; the
// pseudo-inverse keeps the in-plane derivatives exact and leaves d/dz zero.
TEST(VelocityGradient, AFlatNeighbourhoodGivesTheInPlaneGradient) {
  const Real r = 0.01;
  const WendlandKernel kernel(2 * r);
  std::vector<Vec3> x;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) x.push_back(r * Vec3(i + 0.1 * j, j, 0));
  Mat3 A;
  A << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  std::vector<KernelNeighbor> neighbors;
  std::vector<Vec3> dv;
  const Vec3 center = x[12];
  for (const Vec3& xb : x) {
    const Vec3 offset = xb - center;
    if (offset.isZero() || offset.norm() >= kernel.h) continue;
    neighbors.push_back({offset, r * r * r});
    dv.push_back(A * offset);
  }
  const Mat3 gradient = velocity_gradient(kernel, kernel_correction(kernel, neighbors), neighbors, dv);
  EXPECT_LT((gradient.leftCols<2>() - A.leftCols<2>()).norm(), 1e-12 * A.norm());
  EXPECT_LT(gradient.col(2).norm(), 1e-12 * A.norm());
}

}  // namespace
}  // namespace moreau
