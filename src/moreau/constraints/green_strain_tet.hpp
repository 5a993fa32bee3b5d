#pragma once
// St. Venant-Kirchhoff tetrahedra as constraints (Servin, Lacoursiere & Melin 2006, "Interactive
// simulation of elastic deformable materials"): the rows are the Green strain in Voigt form,
//   E = (F^T F - I) / 2,  C = (E11, E22, E33, 2 E23, 2 E13, 2 E12)   (engineering shears),
// and the compliance is (V0 D)^-1 with D the isotropic elasticity matrix
//   D = [[l + 2m, l, l], [l, l + 2m, l], [l, l, l + 2m]] (+) m I3,  l, m Lame's parameters,
// so the stored energy 0.5 C^T alpha^-1 C = V0 (m E:E + l/2 tr(E)^2) is St. Venant-Kirchhoff's.
// Unlike the stable Neo-Hookean pair (neo_hookean_tet.hpp), whose two rows are far from zero at
// rest and balance each other, these rows vanish at rest: a solver that linearises them once per
// step (the velocity-level formulation) sees no prestress whose geometric stiffness it would miss.
//   dE_jj/dF = F e_j e_j^T,  d(2 E_jk)/dF = F (e_j e_k^T + e_k e_j^T),
// and each row's vertex gradients follow from dC/dF (tet_kinematics.hpp).
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"

namespace moreau {

struct GreenStrainTetConstraints {
  static constexpr std::string_view kName = "green_strain", kErrorName = "green_strain";
  using Multiplier = Eigen::Matrix<Real, 6, 1>;
  using Rows = RowBlock<4, 6>;

  std::vector<std::array<Index, 4>> particles;
  std::vector<Mat3> rest_inverse;     // D_m^-1, 1/m
  std::vector<Rows::Compliance> compliance;  // (V0 D)^-1, 1/J
  std::vector<Real> damping_time;     // s
  std::vector<Index> object;
  ColorBatches batches;

  size_t size() const { return particles.size(); }
  void add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest, Real youngs_modulus, Real poisson_ratio,
           Real tau, Index obj);
  void color(const std::vector<Real>& particle_inv_mass);
  Rows rows(Index k, const Vec3* x) const;
  /// sum V0 (mu E:E + lambda/2 tr(E)^2), J.
  Real energy(const Vec3* x, Index object) const;
  /// The largest |Green strain| component (engineering shears halved).
  Real max_error(const Vec3* x, Index object) const;
};

/// Voigt order of the rows: the index pairs (j, k) of E_jk, normal strains first, then the shears.
inline constexpr int kVoigtPair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

/// The Green-strain rows of tetrahedron `particles` at deformation gradient F: C and each vertex's
/// 6 x 3 gradient (no compliance, no damping).
GreenStrainTetConstraints::Rows green_strain_rows(const std::array<Index, 4>& particles, const Mat3& F,
                                                  const Mat3& rest_inverse);

}  // namespace moreau
