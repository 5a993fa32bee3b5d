#include "moreau/materials/hyperelastic.hpp"

#include <cmath>
#include <limits>

namespace moreau {

namespace {

// Voigt index p -> tensor indices (I, J).
constexpr int kVoigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};

// CC_IJKL = a X_IJ X_KL + b (X_IK X_JL + X_IL X_JK) for a symmetric X, in Voigt order.
Mat6 product_plus_symmetric(const Mat3& X, Real a, Real b) {
  Mat6 D;
  for (int p = 0; p < 6; ++p)
    for (int q = 0; q < 6; ++q) {
      const int I = kVoigt[p][0], J = kVoigt[p][1], K = kVoigt[q][0], L = kVoigt[q][1];
      D(p, q) = a * X(I, J) * X(K, L) + b * (X(I, K) * X(J, L) + X(I, L) * X(J, K));
    }
  return D;
}

}  // namespace

LameParameters lame_from_youngs(Real E, Real nu) {
  return {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
}

Vec6 to_voigt(const Mat3& A) {
  Vec6 v;
  for (int p = 0; p < 6; ++p) v[p] = A(kVoigt[p][0], kVoigt[p][1]);
  return v;
}

Mat3 from_voigt(const Vec6& v) {
  Mat3 A;
  for (int p = 0; p < 6; ++p) A(kVoigt[p][0], kVoigt[p][1]) = A(kVoigt[p][1], kVoigt[p][0]) = v[p];
  return A;
}

Mat3 green_lagrange_strain(const Mat3& H) { return 0.5 * (H + H.transpose() + H.transpose() * H); }

Real det_identity_plus_minus_one(const Mat3& X) {
  const Real t = X.trace();
  return t + 0.5 * (t * t - (X * X).trace()) + X.determinant();
}

Mat6 pressure_stress_tangent(const Mat3& C_inverse, Real pJ) { return product_plus_symmetric(C_inverse, pJ, -pJ); }

HyperelasticResponse HyperelasticMaterial::respond(const Mat3& E, bool with_tangent) const {
  const Real lambda = lame.lambda, mu = lame.mu;
  HyperelasticResponse r;
  if (model == HyperelasticModel::st_venant_kirchhoff) {
    const Real trE = E.trace();
    r.energy = 0.5 * lambda * trE * trE + mu * E.squaredNorm();
    r.stress = to_voigt(lambda * trE * Mat3::Identity() + 2 * mu * E);
    if (with_tangent) r.tangent = product_plus_symmetric(Mat3::Identity(), lambda, mu);
    return r;
  }
  const Real detC_minus_one = det_identity_plus_minus_one(2 * E);
  if (!(detC_minus_one > -1)) {
    r.valid = false;
    r.energy = std::numeric_limits<Real>::infinity();
    r.stress.setZero();
    if (with_tangent) r.tangent.setZero();
    return r;
  }
  const Real lnJ = 0.5 * std::log1p(detC_minus_one);
  const Mat3 Cinv = (Mat3::Identity() + 2 * E).inverse();
  r.energy = mu * (E.trace() - lnJ) + 0.5 * lambda * lnJ * lnJ;
  r.stress = to_voigt(2 * mu * Cinv * E + lambda * lnJ * Cinv);
  if (with_tangent) r.tangent = product_plus_symmetric(Cinv, lambda, mu - lambda * lnJ);
  return r;
}

HyperelasticMaterial HyperelasticMaterial::without_volumetric_energy() const {
  HyperelasticMaterial rest = *this;
  rest.lame.lambda = 0;
  return rest;
}

// U = lambda/2 (ln J)^2,  U' = lambda ln J / J,  U'' = lambda (1 - ln J) / J^2.
HyperelasticMaterial::Volumetric HyperelasticMaterial::volumetric_energy(Real J_minus_one) const {
  const Real J = 1 + J_minus_one, lnJ = std::log1p(J_minus_one), lambda = lame.lambda;
  return {0.5 * lambda * lnJ * lnJ, lambda * lnJ / J, lambda * (1 - lnJ) / (J * J)};
}

Real HyperelasticMaterial::energy(const Mat3& E) const { return respond(E, false).energy; }

Mat3 HyperelasticMaterial::stress(const Mat3& E) const { return from_voigt(respond(E, false).stress); }

}  // namespace moreau
