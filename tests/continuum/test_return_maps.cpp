// Return maps (continuum/return_maps.hpp): states inside the yield surface are left alone, states
// outside land on it with their volume kept, and the surfaces mean what their parameters say: the
// Drucker-Prager cone meets Mohr-Coulomb in triaxial compression, and a von Mises state yields at
// its uniaxial yield stress. Checked in the Kirchhoff stress of the elastic law, not in the
// strain the maps work in.
#include <gtest/gtest.h>

#include <random>

#include "moreau/continuum/return_maps.hpp"

namespace moreau {
namespace {

const LameParameters kSand = lame_from_youngs(1e4, 0.3);
constexpr Real kPhi = 35 * kPi / 180;  // friction angle

Vec3 deviator(const Vec3& x) { return x - (x.sum() / 3) * Vec3::Ones(); }

// The Drucker-Prager function |tau^| + alpha tr tau (Pa): <= 0 inside the cone.
Real drucker_prager_function(const Vec3& sigma) {
  const Vec3 tau = hencky_kirchhoff(kSand, sigma);
  return deviator(tau).norm() + drucker_prager_alpha(kPhi) * tau.sum();
}

Vec3 random_stretches(std::mt19937& rng, Real spread) {
  std::uniform_real_distribution<Real> log_stretch(-spread, spread);
  return Vec3(std::exp(log_stretch(rng)), std::exp(log_stretch(rng)), std::exp(log_stretch(rng)));
}

TEST(ReturnMaps, DruckerPragerLeavesTheConeAloneAndReturnsOntoIt) {
  std::mt19937 rng(17);
  int inside = 0, returned = 0, tip = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 sigma = random_stretches(rng, 0.2);
    const PlasticReturn r = drucker_prager_return(kSand, kPhi, sigma);
    const Real before = drucker_prager_function(sigma), after = drucker_prager_function(r.sigma);
    const Real scale = hencky_kirchhoff(kSand, sigma).norm();
    if (hencky_strain(sigma).sum() > 0) {  // tension: no stress
      ++tip;
      EXPECT_EQ(r.sigma, Vec3::Ones());
    } else if (before <= 0) {
      ++inside;
      EXPECT_EQ(r.sigma, sigma);
      EXPECT_EQ(r.plastic_strain, 0);
    } else {
      ++returned;
      EXPECT_NEAR(after, 0, 1e-12 * scale);                                           // on the cone
      EXPECT_NEAR(r.sigma.prod(), sigma.prod(), 1e-12);                               // J kept
      EXPECT_NEAR(deviator(hencky_strain(r.sigma)).normalized().dot(deviator(hencky_strain(sigma)).normalized()), 1,
                  1e-12);                                                             // radial
      EXPECT_GT(r.plastic_strain, 0);
    }
  }
  std::printf("Drucker-Prager, phi = 35 deg: %d states inside, %d returned onto the cone, %d in tension\n", inside,
              returned, tip);
  EXPECT_GT(inside, 100);
  EXPECT_GT(returned, 100);
  EXPECT_GT(tip, 100);
}

// Triaxial compression: lateral stretch s_l, axial s_a < s_l. Squeezed past yield, the returned
// state's principal stresses (compressions a = -tau_lateral < b = -tau_axial) satisfy
// Mohr-Coulomb's (b - a) / (b + a) = sin phi for phi = 20, 35, 45 degrees.
TEST(ReturnMaps, DruckerPragerConeMeetsMohrCoulombInTriaxialCompression) {
  for (const Real degrees : {20.0, 35.0, 45.0}) {
    const Real phi = degrees * kPi / 180;
    const Vec3 sigma(1.04, 1.04, 0.85);  // squeezed along z, bulging sideways: past yield for every phi here
    const PlasticReturn r = drucker_prager_return(kSand, phi, sigma);
    ASSERT_GT(r.plastic_strain, 0) << degrees;
    const Vec3 tau = hencky_kirchhoff(kSand, r.sigma);
    const Real a = -tau[0], b = -tau[2];
    std::printf("triaxial compression at phi = %.0f deg: (b - a)/(b + a) = %.12f, sin phi = %.12f\n", degrees,
                (b - a) / (b + a), std::sin(phi));
    EXPECT_NEAR(tau[0], tau[1], 1e-12 * b);
    EXPECT_NEAR((b - a) / (b + a), std::sin(phi), 1e-12);
  }
}

TEST(ReturnMaps, VonMisesYieldsAtTheUniaxialYieldStressAndKeepsTheVolume) {
  const LameParameters metal = lame_from_youngs(2e11, 0.3);
  const Real yield = 2.5e8;  // Pa
  std::mt19937 rng(23);
  int inside = 0, returned = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 sigma = random_stretches(rng, 0.004);
    const PlasticReturn r = von_mises_return(metal, yield, sigma);
    const Real before = std::sqrt(1.5) * deviator(hencky_kirchhoff(metal, sigma)).norm();
    const Real after = std::sqrt(1.5) * deviator(hencky_kirchhoff(metal, r.sigma)).norm();
    if (before <= yield) {
      ++inside;
      EXPECT_EQ(r.sigma, sigma);
    } else {
      ++returned;
      // The von Mises stress at yield: exact but for the rounding of ln and exp of stretches near 1
      // (1e-16 absolute on strains of 1e-3, 1e-13 of the stress); 1e-9 leaves room.
      EXPECT_NEAR(after, yield, 1e-9 * yield);
      EXPECT_NEAR(r.sigma.prod(), sigma.prod(), 1e-12);
    }
  }
  // A bar pulled along x (lateral stretches keeping tau_y = tau_z = 0 elastically, nu = 0.3)
  // yields when its axial stress reaches the yield stress.
  const Real strain = 2e-3, lateral = -0.3 * strain;
  const Vec3 bar(std::exp(strain), std::exp(lateral), std::exp(lateral));
  const Vec3 tau = hencky_kirchhoff(metal, bar);
  const PlasticReturn r = von_mises_return(metal, yield, bar);
  const Vec3 flowed = hencky_kirchhoff(metal, r.sigma);
  std::printf("von Mises: %d inside, %d returned; a bar at %.3e axial stress (%.3e lateral) flows back to %.6e "
              "Pa of axial minus lateral stress (yield %.3e)\n",
              inside, returned, tau[0], tau[1], flowed[0] - flowed[1], yield);
  EXPECT_GT(inside, 100);
  EXPECT_GT(returned, 100);
  EXPECT_NEAR(tau[1], 0, 1e-6 * tau[0]);                     // uniaxial stress to first order
  EXPECT_NEAR(flowed[0] - flowed[1], yield, 1e-9 * yield);  // sqrt(3/2)|tau^| = tau_x - tau_y for this state
}

// Snow (Stomakhin et al. 2013): stretches outside [1 - theta_c, 1 + theta_s] are clamped, the
// plastic volume ratio grows by det(trial) / det(clamped), so that J_p J_e keeps the total
// volume, and compaction (J_p < 1) stiffens by exp(xi (1 - J_p)).
TEST(SnowReturn, ClampsTheStretchesAndKeepsTheTotalVolumeInTheTwoParts) {
  const Real theta_c = 0.025, theta_s = 0.0075;
  const Vec3 inside(1.005, 0.99, 0.98);
  const PlasticReturn elastic = snow_return(theta_c, theta_s, inside);
  EXPECT_EQ(elastic.sigma, inside);
  EXPECT_EQ(elastic.plastic_volume_factor, 1);
  EXPECT_EQ(elastic.plastic_strain, 0);
  const Vec3 trial(1.02, 0.99, 0.9);  // stretched past 1 + theta_s, compressed past 1 - theta_c
  const PlasticReturn r = snow_return(theta_c, theta_s, trial);
  EXPECT_EQ(r.sigma, Vec3(1 + theta_s, 0.99, 1 - theta_c));
  EXPECT_NEAR(r.plastic_volume_factor * r.sigma.prod(), trial.prod(), 1e-15);
  EXPECT_NEAR(r.plastic_strain, std::hypot(std::log(1.02 / 1.0075), std::log(0.9 / 0.975)), 1e-15);
  const LameParameters m{2.0, 3.0};
  const LameParameters compacted = snow_hardened(m, 10, 0.9);
  EXPECT_NEAR(compacted.mu, 3.0 * std::exp(1.0), 1e-12);
  EXPECT_NEAR(compacted.lambda, 2.0 * std::exp(1.0), 1e-12);
}

// Cohesion moves the cone's tip to an isotropic tension whose mean Kirchhoff stress is the
// cohesion: a particle stretched beyond it returns to that stress; one inside keeps its state.
TEST(DruckerPragerReturn, CohesionCarriesAnIsotropicTensionUpToIt) {
  const LameParameters sand = lame_from_youngs(1e5, 0.3);
  const Real phi = 30 * kPi / 180, cohesion = 50;
  const PlasticReturn pulled = drucker_prager_return(sand, phi, Vec3::Constant(1.01), cohesion);
  EXPECT_NEAR(hencky_kirchhoff(sand, pulled.sigma).mean(), cohesion, 1e-9 * cohesion);
  const Vec3 small = Vec3::Constant(1 + 1e-5);  // mean stress (3 lambda + 2 mu) 1e-5 = 2.5 Pa
  EXPECT_EQ(drucker_prager_return(sand, phi, small, cohesion).sigma, small);
  EXPECT_EQ(drucker_prager_return(sand, phi, small).sigma, Vec3::Ones());  // without cohesion: the tip
}

}  // namespace
}  // namespace moreau
