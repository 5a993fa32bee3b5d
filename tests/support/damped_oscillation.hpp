#pragma once
// A damped oscillation fitted to a sampled signal: the l = 2 shape oscillation of a drop (surface
// and interfacial tension tests).
#include <cmath>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau::test {

struct DampedOscillation {
  Real decay, frequency;  // alpha (1/s) and omega_d (rad/s) of c + e^(-alpha t) (a cos omega_d t + b sin omega_d t)
  Real natural() const { return std::sqrt(frequency * frequency + decay * decay); }  // omega_0
};

// Least squares fit of c + e^(-alpha t)(a cos w t + b sin w t) to q(t): (c, a, b) solved exactly for
// each (alpha, w) of a grid (alpha 0-30 1/s by 0.25, w 2-80 rad/s by 0.1), the best pair kept. The
// residual is q.q - coef.b at the normal equations' solution.
inline DampedOscillation fit_damped_oscillation(const std::vector<Real>& t, const std::vector<Real>& q) {
  const size_t m = t.size();
  Real qq = 0;
  for (Real value : q) qq += value * value;
  std::vector<Real> cosine(m), sine(m), decay(121 * m);  // decay[ia * m + k] = e^(-alpha_ia t_k)
  for (int ia = 0; ia <= 120; ++ia)
    for (size_t k = 0; k < m; ++k) decay[ia * m + k] = std::exp(-0.25 * ia * t[k]);
  DampedOscillation best{0, 0};
  Real best_error = INFINITY;
  for (int iw = 0; iw <= 780; ++iw) {
    const Real w = 2 + 0.1 * iw;
    for (size_t k = 0; k < m; ++k) cosine[k] = std::cos(w * t[k]), sine[k] = std::sin(w * t[k]);
    for (int ia = 0; ia <= 120; ++ia) {
      const Real alpha = 0.25 * ia;
      Mat3 A = Mat3::Zero();
      Vec3 b = Vec3::Zero();
      for (size_t k = 0; k < m; ++k) {
        const Real e = decay[ia * m + k];
        const Vec3 basis(1, e * cosine[k], e * sine[k]);
        A += basis * basis.transpose();
        b += q[k] * basis;
      }
      const Real error = qq - A.ldlt().solve(b).dot(b);
      if (error < best_error) best_error = error, best = {alpha, w};
    }
  }
  return best;
}

}  // namespace moreau::test
