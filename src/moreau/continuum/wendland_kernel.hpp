#pragma once
// The Wendland C2 smoothing kernel in 3D (Wendland 1995), the kernel of the inelastic continua
// (XPBI, Yu et al. 2024), with compact support h (zero for r >= h):
//   q = r / h,   W(r) = 21 / (2 pi h^3) (1 - q)^4 (1 + 4 q),
//   dW/dr = 21 / (2 pi h^4) (-20 q (1 - q)^3),
// so grad W(r_vec) = r_vec dW/dr / r = -210 / (pi h^5) (1 - q)^3 r_vec, finite at r = 0. It
// integrates to one over its support.
#include "moreau/math/types.hpp"

namespace moreau {

struct WendlandKernel {
  Real h = 1, inv_h = 1, sigma = 21 / (2 * kPi);

  explicit WendlandKernel(Real support = 1)
      : h(support), inv_h(1 / support), sigma(21 / (2 * kPi * support * support * support)) {}

  /// W at distance r (m) -> 1/m^3.
  Real value(Real r) const {
    const Real q = r * inv_h;
    if (q >= 1) return 0;
    const Real a = 1 - q;
    return sigma * a * a * a * a * (1 + 4 * q);
  }

  /// dW/dr / r (1/m^5): grad W(r_vec) = r_vec * gradient_factor(r).
  Real gradient_factor(Real r) const {
    const Real q = r * inv_h;
    if (q >= 1) return 0;
    const Real a = 1 - q;
    return -20 * sigma * inv_h * inv_h * a * a * a;
  }
};

}  // namespace moreau
