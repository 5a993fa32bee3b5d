#pragma once
// Isometric bending constraints on the hinges of a surface that is flat at rest.
//
// Bergou, Wardetzky, Harmon, Zorin, Grinspun 2006, "A quadratic bending model for inextensible
// surfaces": for isometric (non-stretching) deformations of a flat rest shape the hinge bending
// energy is quadratic in the positions. We write it as one vector constraint per hinge
//   C = sum_i K_i x_i                                  (m, a 3-vector; 0 for any planar placement)
//   grad_{x_i} C = K_i I                               (constant)
// with the weights K the affine dependency of the four flat rest points (sum K_i = 0,
// sum K_i X_i = 0), scaled so that |C| = l theta to first order in the dihedral angle theta:
//   K_o0 = l^2 / (2 A_A),  K_o1 = l^2 / (2 A_B),                (A_A, A_B: rest triangle areas)
//   K_e1 = -(K_o0 a_0 + K_o1 a_1) / l,  a_j = (O_j - E0) . e / l,   K_e0 = -(K_e1 + K_o0 + K_o1).
// (Lifting o0 by d out of the plane gives theta = d / h_A and C = K_o0 d = l theta, h_A = 2 A_A / l.)
// Compliance alpha (m/N): energy |C|^2 / (2 alpha). A hinge is given the per-angle compliance
// alpha_theta (1/(N m)) of the dihedral model (dihedral_bending.hpp, from k_B or set directly);
// since |C| = l theta, alpha = l^2 alpha_theta gives the same energy to O(theta^2).
// Because the gradient is constant the XPBD system is diagonal (one scalar for all three
// components) and the projection needs no square root, division by |n| or arc tangent.
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"
#include "moreau/geometry/meshes.hpp"

namespace moreau {

/// One hinge's projection data, packed (built by color()).
struct IsometricHinge {
  std::array<Index, 4> particles;  // e0, e1, o0, o1
  std::array<Real, 4> weight;      // K_i (dimensionless)
  Real compliance;                 // m/N
  Real damping_time;               // s
};

struct IsometricBendingConstraints {
  static constexpr std::string_view kName = "isometric_bending", kErrorName = "bending";
  using Multiplier = Vec3;
  using Rows = RowBlock<4, 3>;

  std::vector<IsometricHinge> hinges;
  std::vector<Real> edge_length;  // m, rest length of the hinge edge (reports |C| / l in rad)
  std::vector<Index> object;
  ColorBatches batches;

  size_t size() const { return hinges.size(); }
  /// Adds a hinge whose rest points (E0, E1, O0, O1) lie in one plane, with the per-angle
  /// compliance alpha_theta (1/(N m)) a dihedral hinge would have.
  void add(const Hinge& h, const Vec3& E0, const Vec3& E1, const Vec3& O0, const Vec3& O1, Real angle_compliance,
           Real tau, Index obj);
  void color(const std::vector<Real>& particle_inv_mass);
  /// C = sum_i K_i x_i (three rows), gradient K_i I, compliance alpha I.
  Rows rows(Index k, const Vec3* x) const;
  /// sum 0.5 |C|^2 / alpha over compliant hinges, J.
  Real energy(const Vec3* x, Index object) const;
  /// max |C| / l (the dihedral angle to first order), rad.
  Real max_error(const Vec3* x, Index object) const;
};

/// The weights K of a flat rest hinge (see the header comment).
std::array<Real, 4> isometric_hinge_weights(const Vec3& E0, const Vec3& E1, const Vec3& O0, const Vec3& O1);

/// C = sum_i K_i x_i of hinge k.
[[gnu::always_inline]] inline Vec3 isometric_bending_value(const IsometricHinge& h, const Vec3* x) {
  const auto& p = h.particles;
  const auto& K = h.weight;
  return K[0] * x[p[0]] + K[1] * x[p[1]] + K[2] * x[p[2]] + K[3] * x[p[3]];
}

/// lambda holds one 3-vector per hinge.
/// max |C| / l (rad, the small-angle dihedral angle) over the hinges of `object`.

}  // namespace moreau
