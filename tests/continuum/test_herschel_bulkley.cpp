// Herschel-Bulkley viscoplasticity (continuum/return_maps.hpp) against its defining law: a
// material point sheared at a steady rate gamma' carries the shear stress tau_y + K gamma'^n,
// whatever the step; below yield it is elastic; without consistency it is von Mises plasticity.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "moreau/continuum/return_maps.hpp"

namespace moreau {
namespace {

// Stiff enough that the elastic strain at these stresses (< 1e-3) leaves the finite-strain terms
// of the law below the tolerance.
const LameParameters kPaste = lame_from_youngs(2e5, 0.3);
constexpr Real kYield = 50;  // Pa, tau_y

// Shears a material point at rate `rate` (1/s) in steps of h, returning after each, to a total
// shear of 2, and gives its shear Kirchhoff stress tau_xy (Pa) then.
Real steady_shear_stress(Real consistency, Real flow_index, Real rate, Real h) {
  Mat3 velocity_gradient = Mat3::Zero();
  velocity_gradient(0, 1) = rate;
  Mat3 F = Mat3::Identity();
  const int steps = static_cast<int>(std::lround(2 / (rate * h)));
  for (int step = 0; step < steps; ++step) {
    const RotationSvd trial = rotation_svd((Mat3::Identity() + h * velocity_gradient) * F);
    const PlasticReturn r = herschel_bulkley_return(kPaste, kYield, consistency, flow_index, h, trial.sigma);
    F = trial.U * r.sigma.asDiagonal() * trial.V.transpose();
  }
  const RotationSvd now = rotation_svd(F);
  const Mat3 kirchhoff = now.U * hencky_kirchhoff(kPaste, now.sigma).asDiagonal() * now.U.transpose();
  return kirchhoff(0, 1);
}

// tau_xy = tau_y + K gamma'^n in steady simple shear, for a Bingham fluid (n = 1), a shear-thinning
// (n = 0.5) and a shear-thickening one (n = 2), at two rates and two steps each. The law is met
// to the elastic strain's finite-strain terms (< 1e-3 here); 0.5 % bounds them with margin.
TEST(HerschelBulkleyReturn, SteadySimpleShearCarriesTheYieldStressPlusTheRateTerm) {
  struct Fluid {
    Real consistency, flow_index;
  };
  for (const Fluid fluid : {Fluid{2, 1}, Fluid{10, 0.5}, Fluid{0.5, 2}})
    for (const Real rate : {3.0, 12.0})
      for (const Real h : {1e-4, 1e-3}) {
        const Real expected = kYield + fluid.consistency * std::pow(rate, fluid.flow_index);
        EXPECT_NEAR(steady_shear_stress(fluid.consistency, fluid.flow_index, rate, h), expected, 5e-3 * expected)
            << "K " << fluid.consistency << " n " << fluid.flow_index << " rate " << rate << " h " << h;
      }
}

TEST(HerschelBulkleyReturn, BelowYieldItIsElasticAndWithoutConsistencyItIsVonMises) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> log_stretch(-8e-4, 8e-4);
  int yielded = 0;
  for (int k = 0; k < 500; ++k) {
    const Vec3 sigma(std::exp(log_stretch(rng)), std::exp(log_stretch(rng)), std::exp(log_stretch(rng)));
    // von Mises' uniaxial yield stress of a shear yield stress tau_y is sqrt(3) tau_y.
    const PlasticReturn rate_free = von_mises_return(kPaste, std::sqrt(Real(3)) * kYield, sigma);
    const PlasticReturn bulkley = herschel_bulkley_return(kPaste, kYield, 0, 1, 1e-3, sigma);
    const PlasticReturn bulkley_thinning = herschel_bulkley_return(kPaste, kYield, 0, 0.4, 1e-3, sigma);
    EXPECT_LT((bulkley.sigma - rate_free.sigma).norm(), 1e-14);
    EXPECT_LT((bulkley_thinning.sigma - rate_free.sigma).norm(), 1e-12);
    EXPECT_NEAR(bulkley.plastic_strain, rate_free.plastic_strain, 1e-14);
    const PlasticReturn viscous = herschel_bulkley_return(kPaste, kYield, 5, 0.7, 1e-3, sigma);
    if (rate_free.plastic_strain == 0) {
      EXPECT_EQ(viscous.sigma, sigma);  // below yield: untouched
    } else {
      ++yielded;  // the viscous stress holds it between the trial and the rate-free return
      EXPECT_GT(viscous.plastic_strain, 0);
      EXPECT_LT(viscous.plastic_strain, rate_free.plastic_strain);
    }
  }
  EXPECT_GT(yielded, 50);
  EXPECT_LT(yielded, 450);
}

}  // namespace
}  // namespace moreau
