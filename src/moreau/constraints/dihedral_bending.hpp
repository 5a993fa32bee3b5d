#pragma once
// Dihedral bending constraints on the hinges of a triangle surface.
//
// Hinge: shared edge (e0, e1), opposite vertices o0 (triangle e0,e1,o0) and o1 (triangle e1,e0,o1).
//   nA = (e1-e0) x (o0-e0),  nB = (o1-e0) x (e1-e0),  e = e1 - e0,  l = |e|
//   theta = atan2((nA^ x nB^) . e^, nA^ . nB^)       (signed dihedral angle, 0 when flat)
//   C = theta - theta0                                (rad)
//   grad_o0 = -l nA/|nA|^2,   grad_o1 = -l nB/|nB|^2
//   grad_e0 = -((o0-e1).e/l) nA/|nA|^2 - ((o1-e1).e/l) nB/|nB|^2
//   grad_e1 =  ((o0-e0).e/l) nA/|nA|^2 + ((o1-e0).e/l) nB/|nB|^2
//   (Bridson, Marino, Fedkiw 2003, "Simulation of clothing with folds and wrinkles", sec. 4.2;
//    signs fixed by our finite-difference test.)
//   compliance alpha (rad^2/J = 1/(N m)). From a bending stiffness k_B (N m) of the plate energy
//   (k_B/2) int kappa^2 dA we take the hinge energy (k_B/2) l^2/(A_A + A_B) (theta - theta0)^2, so
//   alpha = (A_A + A_B) / (k_B l^2).
//   Calibration: a sheet rolled onto a cylinder of radius R about a mesh-edge direction then has
//   energy (k_B/2) A/R^2 (tests/constraints/test_bending_models.cpp). The discrete-shells weight
//   3 l^2/(A_A + A_B) (Grinspun et al. 2003) makes that 3x too stiff: only one edge family in
//   three carries a cylindrical bend, so the curvature lives in a third of the area. Hinge
//   bending stays anisotropic: on moreau's grid sheet, rolling about a diagonal is 1.5x stiffer.
#include <cmath>
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"
#include "moreau/geometry/meshes.hpp"

namespace moreau {

struct DihedralBendingConstraints {
  static constexpr std::string_view kName = "dihedral_bending", kErrorName = "bending";
  using Multiplier = Real;
  using Rows = RowBlock<4, 1>;

  std::vector<Hinge> hinges;
  std::vector<Real> rest_angle;    // rad
  std::vector<Real> compliance;    // 1/(N m)
  std::vector<Real> damping_time;  // s
  std::vector<Index> object;
  ColorBatches batches;

  size_t size() const { return hinges.size(); }
  void add(const Hinge& h, Real theta0, Real alpha, Real tau, Index obj) {
    hinges.push_back(h);
    rest_angle.push_back(theta0);
    compliance.push_back(alpha);
    damping_time.push_back(tau);
    object.push_back(obj);
  }
  void color(const std::vector<Real>& particle_inv_mass);
  /// C = theta - theta0 wrapped to (-pi, pi], over (e0, e1, o0, o1).
  Rows rows(Index k, const Vec3* x) const;
  /// sum 0.5 C^2 / alpha over compliant hinges, J.
  Real energy(const Vec3* x, Index object) const;
  /// max |theta - theta0|, rad.
  Real max_error(const Vec3* x, Index object) const;
};

struct DihedralValue {
  Real theta;
  std::array<Vec3, 4> grad;  // with respect to e0, e1, o0, o1
};

/// Wraps an angle difference to (-pi, pi] so a hinge never takes the long way round.
inline Real wrap_angle(Real a) {
  while (a > kPi) a -= 2 * kPi;
  while (a <= -kPi) a += 2 * kPi;
  return a;
}

[[gnu::always_inline]] inline DihedralValue evaluate_dihedral(const Vec3& e0, const Vec3& e1, const Vec3& o0, const Vec3& o1) {
  DihedralValue v{0, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}};
  const Vec3 e = e1 - e0;
  const Real l2 = e.squaredNorm();
  const Vec3 nA = e.cross(o0 - e0);
  const Vec3 nB = (o1 - e0).cross(e);
  const Real nA2 = nA.squaredNorm(), nB2 = nB.squaredNorm();
  if (l2 <= 0 || nA2 <= 0 || nB2 <= 0) return v;  // degenerate hinge: no bending direction
  const Real l = std::sqrt(l2), inv_l = 1 / l;
  // atan2 is invariant to scaling both arguments by |nA||nB| > 0, so the normals need no normalizing.
  v.theta = std::atan2(nA.cross(nB).dot(e) * inv_l, nA.dot(nB));
  const Vec3 gA = nA * (1 / nA2), gB = nB * (1 / nB2);
  v.grad[2] = -l * gA;
  v.grad[3] = -l * gB;
  // (o - e1).e = (o - e0).e - l^2
  const Real sA = (o0 - e0).dot(e) * inv_l, sB = (o1 - e0).dot(e) * inv_l;
  v.grad[0] = (l - sA) * gA + (l - sB) * gB;
  v.grad[1] = sA * gA + sB * gB;
  return v;
}

/// Hinge compliance for a bending stiffness k_B (N m), from the discrete-shells energy above.
Real hinge_compliance_from_bending_stiffness(const Vec3& e0, const Vec3& e1, const Vec3& o0, const Vec3& o1,
                                             Real bending_stiffness);


}  // namespace moreau
