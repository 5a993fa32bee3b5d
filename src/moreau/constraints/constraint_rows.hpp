#pragma once
// Constraint rows: what every solver reads from a constraint family.
//
// Constraint k of a family is a block of R scalar rows C_r(x) over P particles. A family's
// rows(k, x) evaluates it at positions x and returns
//   C            the row values (in the family's units: m, rad, strain, ...),
//   gradient     gradient[i].row(r) = dC_r/dx_i, an R x 3 block per particle,
//   compliance   alpha, symmetric R x R (units of C^2/J): the stored energy is 0.5 C^T alpha^-1 C,
//                alpha = 0 makes the rows hard,
//   damping_time tau (s): Kelvin-Voigt damping, the force -(tau/alpha) dC/dt (XPBD eq. 26 with
//                beta = tau/alpha, Macklin et al. 2016),
//   lower/upper  bounds on each row's multiplier: (-inf, inf) for a bilateral row, one side
//                finite for a unilateral (contact) row, a friction cone for friction rows.
// A solver never looks inside a family: XPBD projects the rows (solvers/xpbd/project_rows.hpp),
// a velocity-level solver assembles the same rows into its system.
#include <array>
#include <limits>

#include "moreau/math/types.hpp"

namespace moreau {

template <int P, int R>
struct RowBlock {
  static constexpr int kParticles = P, kRows = R;
  using Vector = Eigen::Matrix<Real, R, 1>;
  using Gradient = Eigen::Matrix<Real, R, 3>;
  using Compliance = Eigen::Matrix<Real, R, R>;

  std::array<Index, P> particle{};
  Vector C = Vector::Zero();
  std::array<Gradient, P> gradient{};
  Compliance compliance = Compliance::Zero();
  Real damping_time = 0;
  Vector lower = Vector::Constant(-std::numeric_limits<Real>::infinity());
  Vector upper = Vector::Constant(std::numeric_limits<Real>::infinity());
};

}  // namespace moreau
