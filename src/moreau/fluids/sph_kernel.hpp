#pragma once
// The SPH smoothing kernel of the fluid solver: the cubic B-spline of Monaghan & Lattanzio (1985)
// in 3D, with compact support h (zero for r >= h), written in the support-radius form
//   q = r / h,  sigma = 8 / (pi h^3)
//   W(r)  = sigma (6 q^3 - 6 q^2 + 1)   0 <= q <= 1/2
//         = sigma 2 (1 - q)^3           1/2 < q <= 1
//   dW/dr = sigma / h (18 q^2 - 12 q)   0 <= q <= 1/2
//         = sigma / h (-6 (1 - q)^2)    1/2 < q <= 1
//   grad W(r_vec) = dW/dr r_vec / |r_vec|   (gradient with respect to its argument r_vec = x_i - x_j)
// The solver's pair loops evaluate the same polynomial branch-free, several pairs at once
// (pair_chunks.hpp); this scalar form is the reference (set-up, vorticity, tests).
// The same kernel serves density and its gradient, so the density constraint's gradient is the
// exact derivative of its value (PBF's poly6/spiky pair is not). With h = 4 r (r the particle
// radius, lattice spacing 2 r) a particle of a regular lattice sees about 30 neighbours and
// sum_j V_j W_ij = 1 to within 1 % (tests/fluids/test_fluids.cpp measures it).
#include <cmath>

#include "moreau/math/types.hpp"

namespace moreau {

struct CubicSplineKernel {
  Real h = 1, inv_h = 1, sigma = 8 / kPi, h2 = 1;

  explicit CubicSplineKernel(Real support = 1)
      : h(support), inv_h(1 / support), sigma(8 / (kPi * support * support * support)), h2(support * support) {}

  /// W at distance r (m) -> 1/m^3.
  Real value(Real r) const {
    const Real q = r * inv_h;
    if (q >= 1) return 0;
    if (q <= 0.5) return sigma * (6 * q * q * (q - 1) + 1);
    const Real a = 1 - q;
    return sigma * 2 * a * a * a;
  }

  /// dW/dr / r (1/m^5), so that grad W(r_vec) = r_vec * gradient_factor(r). Finite at r = 0.
  Real gradient_factor(Real r) const {
    const Real q = r * inv_h;
    if (q >= 1) return 0;
    const Real scale = sigma * inv_h * inv_h;  // dW/dr / r = sigma / h^2 * (dw/dq) / q
    if (q <= 0.5) return scale * (18 * q - 12);
    const Real a = 1 - q;
    return scale * (-6 * a * a / q);
  }
};

}  // namespace moreau
