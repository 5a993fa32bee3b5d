// The Maxwell fluid's return map (continuum/return_maps.hpp) at a material point, against the
// Maxwell model's closed forms: steady shear carries eta gamma' with eta = mu lambda at any step, a
// held shear relaxes as exp(-t / lambda), and shear started from rest builds its stress as
// eta gamma' (1 - exp(-t / lambda)) (the upper-convected Maxwell model's start-up solution).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "moreau/continuum/return_maps.hpp"

namespace moreau {
namespace {

const LameParameters kPutty = lame_from_youngs(2e5, 0.3);

// The shear Kirchhoff stress tau_xy (Pa) of the elastic deformation gradient F.
Real shear_stress(const Mat3& F) {
  const RotationSvd now = rotation_svd(F);
  const Mat3 kirchhoff = now.U * hencky_kirchhoff(kPutty, now.sigma).asDiagonal() * now.U.transpose();
  return kirchhoff(0, 1);
}

// One step of h of simple shear at `rate` (1/s; 0 holds the shape), then the return map: the
// update XPBI makes of a particle's F, F <- Z((I + h grad v) F).
Mat3 sheared_step(const Mat3& F, Real rate, Real relaxation_time, Real h) {
  Mat3 velocity_gradient = Mat3::Zero();
  velocity_gradient(0, 1) = rate;
  const RotationSvd trial = rotation_svd((Mat3::Identity() + h * velocity_gradient) * F);
  const PlasticReturn r = maxwell_return(kPutty, relaxation_time, h, trial.sigma);
  return trial.U * r.sigma.asDiagonal() * trial.V.transpose();
}

// Steady simple shear: the fixed point of the backward-Euler relaxation carries tau_xy = mu lambda
// gamma' exactly, whether the step is much shorter than lambda (a viscoelastic fluid resolved in
// time) or much longer (a Newtonian fluid of viscosity mu lambda). lambda gamma' <= 1.2e-3 keeps the
// elastic shear strain, lambda gamma' / 2, small enough that the finite-strain terms of the
// Hencky law (of order its square) stay below 1e-5; 1e-4 bounds them.
TEST(MaxwellReturn, SteadyShearIsNewtonianWithViscosityMuLambda) {
  const Real lambda = 1e-4;  // s
  for (const Real rate : {3.0, 12.0})
    for (const Real h : {1e-5, 1e-3}) {
      Mat3 F = Mat3::Identity();
      const int steps = static_cast<int>(std::lround(std::max(2.0, 20 * lambda * rate) / (rate * h)));
      for (int step = 0; step < steps; ++step) F = sheared_step(F, rate, lambda, h);
      const Real expected = kPutty.mu * lambda * rate;
      EXPECT_NEAR(shear_stress(F), expected, 1e-4 * expected) << "rate " << rate << " h " << h;
    }
}

// A shear of 0.01 applied at once and then held: each step multiplies the deviatoric Hencky
// strain, and with it the shear stress, by lambda / (lambda + h) exactly (the shear keeps the
// volume, so the stress has no volumetric part). That product tends to exp(-t / lambda) with an
// error of t h / (2 lambda^2) relative: 0.5 % at t = 2 lambda with h = lambda / 200, halving as h
// halves.
TEST(MaxwellReturn, AHeldShearRelaxesExponentially) {
  const Real lambda = 0.5;
  Mat3 start = Mat3::Identity();
  start(0, 1) = 0.01;
  const Real tau0 = shear_stress(start);
  Real error_before = 0;
  for (const int per_lambda : {200, 400}) {
    const Real h = lambda / per_lambda;
    Mat3 F = start;
    for (int step = 1; step <= 2 * per_lambda; ++step) {
      F = sheared_step(F, 0, lambda, h);
      const Real discrete = std::pow(lambda / (lambda + h), step);
      EXPECT_NEAR(shear_stress(F) / tau0, discrete, 1e-12) << "step " << step;
    }
    const Real exact = std::exp(-2.0), error = shear_stress(F) / tau0 / exact - 1;
    fmt::print("held shear, h = lambda / {}: tau(2 lambda) / tau0 = {:.6f} against exp(-2) = {:.6f} ({:+.3f} %)\n",
               per_lambda, shear_stress(F) / tau0, exact, 100 * error);
    EXPECT_NEAR(error, 2.0 / (2 * per_lambda), 0.05 * 2.0 / (2 * per_lambda));  // the predicted t h / (2 lambda^2)
    if (error_before != 0) {
      EXPECT_NEAR(error_before / error, 2, 0.05);  // first order in h
    }
    error_before = error;
  }
}

// Shear at rate gamma' started from rest: the upper-convected Maxwell model's shear stress is
// eta gamma' (1 - exp(-t / lambda)) at any rate. Our map relaxes ln(F F^T) instead of F F^T, which
// agrees to the Weissenberg number lambda gamma' squared; at 0.01 and with h = lambda / 1000
// (backward Euler's lag, 5e-4 of the stress) the two agree within 0.2 % of eta gamma'.
TEST(MaxwellReturn, StartUpShearBuildsTheUpperConvectedMaxwellStress) {
  const Real lambda = 0.2, rate = 0.05, h = lambda / 1000, eta = kPutty.mu * lambda;
  Mat3 F = Mat3::Identity();
  int step = 0;
  for (const Real t_over_lambda : {0.1, 0.5, 1.0, 2.0, 5.0}) {
    while (step < std::lround(t_over_lambda * 1000)) F = sheared_step(F, rate, lambda, h), ++step;
    const Real expected = eta * rate * (1 - std::exp(-t_over_lambda));
    fmt::print("start-up shear, t = {} lambda: tau_xy {:.4f} Pa against {:.4f} Pa\n", t_over_lambda, shear_stress(F),
               expected);
    EXPECT_NEAR(shear_stress(F), expected, 2e-3 * eta * rate) << "t " << t_over_lambda << " lambda";
  }
}

}  // namespace
}  // namespace moreau
