#pragma once
// Tetrahedral volume constraints (Mueller et al. 2007, PBD; XPBD compliance).
//   C = det F - 1 = V/V0 - 1                      (dimensionless)
//   grad_xk C = columns of cof(F) D_m^-T,  grad_x0 = -(sum)   (equals (1/(6 V0)) x_jk x x_jl)
//   compliance alpha = 1/(K V0) (1/J) for a bulk modulus K (Pa): U = (K V0/2)(J - 1)^2.
//   alpha = 0 makes the tetrahedron incompressible.
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/xpbd_update.hpp"

namespace moreau {

struct TetVolumeConstraints {
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
};

struct TetVolumeValue {
  Real C;
  std::array<Vec3, 4> grad;
};

TetVolumeValue evaluate_tet_volume(const std::array<Vec3, 4>& x, const Mat3& rest_inverse);
void project_tet_volume(const TetVolumeConstraints& c, Real* lambda, const SubstepContext& s);
Real tet_volume_energy(const TetVolumeConstraints& c, const Vec3* x, Index object);
Real tet_volume_max_error(const TetVolumeConstraints& c, const Vec3* x, Index object);

}  // namespace moreau
