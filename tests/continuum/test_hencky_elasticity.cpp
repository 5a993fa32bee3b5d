// St. Venant-Kirchhoff elasticity in the Hencky strain (continuum/hencky_elasticity.hpp): the
// stress is the derivative of the energy, the energy is frame indifferent and zero at rest, and
// small strains give linear elasticity.
#include <gtest/gtest.h>

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
