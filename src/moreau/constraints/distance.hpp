#pragma once
// Distance (stretch) constraints between particle pairs.
//
//   C = |x0 - x1| - l0                          (m)
//   grad_x0 C = n = (x0 - x1)/|x0 - x1|,  grad_x1 C = -n
//   compliance alpha (m/N): the inverse of an axial spring stiffness; 0 = inextensible.
//   Source: Mueller et al. 2007 (PBD); compliance and damping from XPBD (Macklin et al. 2016).
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/xpbd_update.hpp"

namespace moreau {

struct DistanceConstraints {
  std::vector<std::array<Index, 2>> particles;
  std::vector<Real> rest_length;   // m
  std::vector<Real> compliance;    // m/N
  std::vector<Real> damping_time;  // s
  std::vector<Index> object;       // owning object
  ColorBatches batches;

  size_t size() const { return particles.size(); }
  void add(Index a, Index b, Real rest, Real alpha, Real tau, Index obj) {
    particles.push_back({a, b});
    rest_length.push_back(rest);
    compliance.push_back(alpha);
    damping_time.push_back(tau);
    object.push_back(obj);
  }
  /// Sorts the constraints into colour batches (call once after the last add).
  void color(const std::vector<Real>& particle_inv_mass);
};

struct DistanceValue {
  Real C;
  Vec3 grad0;  // grad_x1 C = -grad0
};

DistanceValue evaluate_distance(const Vec3& x0, const Vec3& x1, Real rest_length);

/// One Gauss-Seidel sweep by colour; lambda accumulates within the substep.
void project_distance(const DistanceConstraints& c, Real* lambda, const SubstepContext& s);

/// Elastic energy sum 0.5 C^2 / alpha over compliant constraints of `object` (-1 = all), J.
Real distance_energy(const DistanceConstraints& c, const Vec3* x, Index object);

/// max |C| over the constraints of `object` (-1 = all), m.
Real distance_max_error(const DistanceConstraints& c, const Vec3* x, Index object);

}  // namespace moreau
