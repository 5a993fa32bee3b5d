#pragma once
// Distance (stretch) constraints between particle pairs.
//
//   C = |x0 - x1| - l0                          (m)
//   grad_x0 C = n = (x0 - x1)/|x0 - x1|,  grad_x1 C = -n
//   compliance alpha (m/N): the inverse of an axial spring stiffness; 0 = inextensible.
//   Source: Mueller et al. 2007 (PBD); compliance and damping from XPBD (Macklin et al. 2016).
#include <cmath>
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"

namespace moreau {

struct DistanceValue {
  Real C;
  Vec3 grad0;  // grad_x1 C = -grad0
};

[[gnu::always_inline]] inline DistanceValue evaluate_distance(const Vec3& x0, const Vec3& x1, Real rest_length) {
  const Vec3 d = x0 - x1;
  const Real length = d.norm();
  const Vec3 n = length > 0 ? Vec3(d * (1 / length)) : Vec3::Zero();
  return {length - rest_length, n};
}

struct DistanceConstraints {
  static constexpr std::string_view kName = "distance", kErrorName = "distance";
  using Multiplier = Real;
  using Rows = RowBlock<2, 1>;

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
  Rows rows(Index k, const Vec3* x) const;
  /// Elastic energy sum 0.5 C^2 / alpha over compliant constraints of `object` (-1 = all), J.
  Real energy(const Vec3* x, Index object) const;
  /// max |C| over the constraints of `object` (-1 = all), m.
  Real max_error(const Vec3* x, Index object) const;
};

}  // namespace moreau
