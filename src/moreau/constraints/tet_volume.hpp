#pragma once
// Tetrahedral volume constraints (Mueller et al. 2007, PBD; XPBD compliance).
//   C = det F - 1 = V/V0 - 1                      (dimensionless)
//   grad_xk C = columns of cof(F) D_m^-T,  grad_x0 = -(sum)   (equals (1/(6 V0)) x_jk x x_jl)
//   compliance alpha = 1/(K V0) (1/J) for a bulk modulus K (Pa): U = (K V0/2)(J - 1)^2.
//   alpha = 0 makes the tetrahedron incompressible.
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"
#include "moreau/constraints/tet_kinematics.hpp"

namespace moreau {

struct TetVolumeConstraints {
  static constexpr std::string_view kName = "tet_volume", kErrorName = "tet_volume";
  using Multiplier = Real;
  using Rows = RowBlock<4, 1>;

  std::vector<std::array<Index, 4>> particles;
  std::vector<Mat3> rest_inverse;   // D_m^-1, 1/m
  std::vector<Real> compliance;     // 1/J
  std::vector<Real> damping_time;   // s
  std::vector<Index> object;
  ColorBatches batches;

  size_t size() const { return particles.size(); }
  /// `volume_compliance` is 1/K (1/Pa); the element compliance is volume_compliance / V0.
  void add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest, Real volume_compliance, Real tau, Index obj);
  void color(const std::vector<Real>& particle_inv_mass);
  /// C = det F - 1.
  Rows rows(Index k, const Vec3* x) const;
  /// sum 0.5 C^2 / alpha over compliant elements, J.
  Real energy(const Vec3* x, Index object) const;
  /// max |det F - 1|.
  Real max_error(const Vec3* x, Index object) const;
};

struct TetVolumeValue {
  Real C;
  std::array<Vec3, 4> grad;
};

[[gnu::always_inline]] inline TetVolumeValue evaluate_tet_volume(const std::array<Vec3, 4>& x, const Mat3& rest_inverse) {
  const Mat3 F = tet_deformation_gradient(x[0], x[1], x[2], x[3], rest_inverse);
  return {F.determinant() - 1, tet_vertex_gradients(cofactor(F), rest_inverse)};
}

}  // namespace moreau
