// St. Venant-Kirchhoff elasticity in the Hencky strain (continuum/hencky_elasticity.hpp): the
// stress is the derivative of the energy, the energy is frame indifferent and zero at rest, and
// small strains give linear elasticity.
#include <gtest/gtest.h>

#include <Eigen/SVD>

#include <random>

#include "moreau/continuum/hencky_elasticity.hpp"

namespace moreau {
namespace {

const LameParameters kSand = lame_from_youngs(1e4, 0.3);

Real energy_of(const Mat3& F) { return hencky_energy(kSand, rotation_svd(F).sigma); }

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<Real> g;
  return Eigen::Quaternion<Real>(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// F = R1 diag(s) R2 with stretches in [0.6, 1.5]: no inversion.
Mat3 random_deformation(std::mt19937& rng) {
  std::uniform_real_distribution<Real> stretch(0.6, 1.5);
  return random_rotation(rng) * Vec3(stretch(rng), stretch(rng), stretch(rng)).asDiagonal() * random_rotation(rng);
}

TEST(HenckyElasticity, RotationSvdKeepsRotationsAndRebuildsF) {
  std::mt19937 rng(3);
  for (int k = 0; k < 100; ++k) {
    Mat3 F = random_deformation(rng);
    if (k % 2) F.col(0) = -F.col(0);  // inverted: det F < 0
    const RotationSvd s = rotation_svd(F);
    EXPECT_NEAR(s.U.determinant(), 1, 1e-12);
    EXPECT_NEAR(s.V.determinant(), 1, 1e-12);
    EXPECT_LT((s.compose() - F).norm(), 1e-12);
    EXPECT_EQ(s.sigma[2] < 0, F.determinant() < 0);
  }
}

// The closed-form SVD against Eigen's iterative JacobiSVD where closed forms are weakest: equal
// stretches (the eigenvectors of F^T F are not unique), F within 1e-9 of a rotation, the 0.05
// stretch the continua clamp to, and F of rank two and one. The singular values agree to 1e-12
// of the largest, and U diag(sigma) V^T rebuilds F to 1e-12 of |F|.
TEST(HenckyElasticity, ClosedFormSvdMatchesJacobiSvd) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> tiny(-1e-9, 1e-9);
  auto check = [](const Mat3& F, const char* what) {
    const RotationSvd s = rotation_svd(F);
    const Vec3 reference = Eigen::JacobiSVD<Mat3>(F).singularValues();
    const Real scale = std::max<Real>(reference[0], 1e-300);
    EXPECT_LT((s.sigma.cwiseAbs() - reference).norm(), 1e-12 * scale) << what << "\n" << F;
    EXPECT_LT((s.compose() - F).norm(), 1e-12 * scale) << what << "\n" << F;
    EXPECT_NEAR(s.U.determinant(), 1, 1e-12) << what;
    EXPECT_NEAR(s.V.determinant(), 1, 1e-12) << what;
    // Ordered largest first, up to the round-off that tells equal stretches apart.
    EXPECT_GE(s.sigma[0], s.sigma[1] - 1e-12 * scale) << what;
    EXPECT_GE(s.sigma[1], std::abs(s.sigma[2]) - 1e-12 * scale) << what;
  };
  check(Mat3::Identity(), "identity");
  check(Mat3::Zero(), "zero");
  for (int k = 0; k < 50; ++k) {
    const Mat3 R1 = random_rotation(rng), R2 = random_rotation(rng);
    Mat3 near_rotation = R1;
    for (int i = 0; i < 9; ++i) near_rotation(i) += tiny(rng);
    check(near_rotation, "near a rotation");
    check(R1 * Vec3(1.3, 1.3, 0.7).asDiagonal() * R2, "two equal stretches");
    check(R1 * Vec3(0.9, 0.9, 0.9).asDiagonal() * R2, "three equal stretches");
    check(R1 * Vec3(1.0, 0.05, 0.05).asDiagonal() * R2, "the clamped stretch");
    check(R1 * Vec3(1.2, 0.8, -0.3).asDiagonal() * R2, "inverted");
    check(R1 * Vec3(1.2, 0.8, 0).asDiagonal() * R2, "rank two");
    check(R1 * Vec3(1.2, 0, 0).asDiagonal() * R2, "rank one");
  }
}

// P against central differences of Psi in each entry of F (step 1e-6): within 1e-6 of |P|, the
// truncation of the differences.
TEST(HenckyElasticity, PiolaStressIsTheEnergysDerivative) {
  std::mt19937 rng(5);
  const Real step = 1e-6;
  for (int k = 0; k < 50; ++k) {
    const Mat3 F = random_deformation(rng);
    const Mat3 P = hencky_piola(kSand, rotation_svd(F));
    Mat3 difference;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Mat3 plus = F, minus = F;
        plus(i, j) += step;
        minus(i, j) -= step;
        difference(i, j) = (energy_of(plus) - energy_of(minus)) / (2 * step);
      }
    EXPECT_LT((P - difference).norm(), 1e-6 * P.norm()) << "F =\n" << F;
  }
}

TEST(HenckyElasticity, EnergyIsZeroAtRestAndFrameIndifferent) {
  std::mt19937 rng(9);
  EXPECT_EQ(hencky_energy(kSand, Vec3::Ones()), 0);
  for (int k = 0; k < 50; ++k) {
    const Mat3 F = random_deformation(rng), R = random_rotation(rng);
    EXPECT_NEAR(energy_of(R * F), energy_of(F), 1e-12 * energy_of(F));
    EXPECT_NEAR(energy_of(R), 0, 1e-20);
  }
}

// F = I + e with a small symmetric e: P = 2 mu e + lambda tr(e) I + O(|e|^2), the linear law.
TEST(HenckyElasticity, SmallStrainsGiveLinearElasticity) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> entry(-1, 1);
  for (int k = 0; k < 20; ++k) {
    Mat3 e;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j <= i; ++j) e(i, j) = e(j, i) = 1e-5 * entry(rng);
    const Mat3 P = hencky_piola(kSand, rotation_svd(Mat3::Identity() + e));
    const Mat3 linear = 2 * kSand.mu * e + kSand.lambda * e.trace() * Mat3::Identity();
    EXPECT_LT((P - linear).norm(), 1e-4 * linear.norm());  // relative error O(|e|) = 1e-5
  }
}

}  // namespace
}  // namespace moreau
