#pragma once
// Triangle Green-strain constraints: a St. Venant-Kirchhoff membrane as one vector constraint.
//
// Rest frame: D_m (2x2) holds the rest edges x1-x0, x2-x0 in an orthonormal basis of the rest
// triangle; F = [f1 f2] = [x1-x0, x2-x0] D_m^-1 (3x2); Green strain E = (F^T F - I)/2.
//   C = (E11, E22, 2 E12)                     (Voigt, engineering shear; dimensionless)
//   grad_xk E11 = f1 M_k1,  grad_xk E22 = f2 M_k2,  grad_xk (2E12) = f2 M_k1 + f1 M_k2
//   (M = D_m^-1, k = 1, 2; grad_x0 = -(grad_x1 + grad_x2))
// With plane-stress moduli, Psi = (1/2) C^T K C where
//   K = [[l*+2mu, l*, 0], [l*, l*+2mu, 0], [0, 0, mu]],  l* = E nu/(1-nu^2),  mu = E/(2(1+nu)),
// is exactly the StVK energy density mu E:E + (l*/2)(tr E)^2. The element energy A t Psi is
// U = (1/2) C^T alpha^-1 C with the block compliance alpha = (A t K)^-1 (1/J).
// The 3x3 block is solved at once (XPBD sec. 6.3; Servin et al. 2006), which keeps the Poisson
// coupling that per-component Strain Based Dynamics (Mueller et al. 2014) loses.
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"

namespace moreau {

struct TriangleStrainConstraints {
  static constexpr std::string_view kName = "triangle_strain", kErrorName = "triangle_strain";
  using Multiplier = Vec3;
  using Rows = RowBlock<3, 3>;

  std::vector<std::array<Index, 3>> particles;
  std::vector<Mat2> rest_inverse;   // D_m^-1, 1/m
  std::vector<Mat3> compliance;     // (A t K)^-1, 1/J
  std::vector<Real> damping_time;   // s
  std::vector<Index> object;
  ColorBatches batches;

  size_t size() const { return particles.size(); }
  /// Adds the membrane of rest triangle (x0, x1, x2) with thickness t (m), Young's modulus E (Pa)
  /// and Poisson ratio nu.
  void add(const std::array<Index, 3>& tri, const Vec3& x0, const Vec3& x1, const Vec3& x2, Real youngs_modulus,
           Real poisson_ratio, Real thickness, Real tau, Index obj);
  void color(const std::vector<Real>& particle_inv_mass);
  /// C = (E11, E22, 2 E12), compliance (A t K)^-1.
  Rows rows(Index k, const Vec3* x) const;
  /// sum 0.5 C^T alpha^-1 C, J.
  Real energy(const Vec3* x, Index object) const;
  /// max |C_r| (Green strain).
  Real max_error(const Vec3* x, Index object) const;
};

struct TriangleStrainValue {
  Vec3 C;                        // (E11, E22, 2E12)
  std::array<Mat3, 3> grad;      // grad[i].row(r) = gradient of C_r with respect to vertex i
};

[[gnu::always_inline]] inline TriangleStrainValue evaluate_triangle_strain(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Mat2& M) {
  Mat32 Ds;
  Ds.col(0) = x1 - x0;
  Ds.col(1) = x2 - x0;
  const Mat32 F = Ds * M;
  const Vec3 f1 = F.col(0), f2 = F.col(1);
  TriangleStrainValue v;
  v.C = Vec3(0.5 * (f1.squaredNorm() - 1), 0.5 * (f2.squaredNorm() - 1), f1.dot(f2));
  for (int k = 1; k <= 2; ++k) {
    Mat3& g = v.grad[k];
    g.row(0) = (f1 * M(k - 1, 0)).transpose();
    g.row(1) = (f2 * M(k - 1, 1)).transpose();
    g.row(2) = (f2 * M(k - 1, 0) + f1 * M(k - 1, 1)).transpose();
  }
  v.grad[0] = -(v.grad[1] + v.grad[2]);
  return v;
}


}  // namespace moreau
