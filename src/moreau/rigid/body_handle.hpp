#pragma once
// One end of a contact or joint: a rigid body, a particle (a body without rotation, Mueller et al.
// 2020 sec. 3.7: "soft and rigid bodies couple directly"), or the world. The position-level
// corrections of Mueller 2020 sec. 3.3 are written once against this handle.
//
// Positional correction of size c along unit n at world offsets r1, r2 from the centres:
//   w_k = 1/m_k + (r_k x n)^T I_k^-1 (r_k x n)                                   (eq. 2-3)
//   dlambda = (-c - alpha~ lambda) / (w1 + w2 + alpha~),  alpha~ = alpha / h^2    (eq. 4)
//   p = dlambda n:  x1 += p/m1,  q1 += 1/2 [I1^-1 (r1 x p), 0] q1,  body 2 with -p  (eq. 6-9)
// Angular correction by theta about unit n: w_k = n^T I_k^-1 n, q1 += 1/2 [I1^-1 p, 0] q1 (eq. 11-15).
// I^-1 is applied in the body frame, where it is diagonal.
#include "moreau/math/types.hpp"
#include "moreau/rigid/rigid_bodies.hpp"

namespace moreau {

/// I^-1 v for a world-space v, with I diagonal (`inv_inertia`) in the frame q maps to the world.
inline Vec3 apply_principal_inverse_inertia(const Quat& q, const Vec3& inv_inertia, const Vec3& v) {
  return q * Vec3(inv_inertia.cwiseProduct(q.conjugate() * v));
}

/// World inverse inertia R diag(I^-1) R^T.
inline Mat3 world_inverse_inertia(const Quat& q, const Vec3& inv_inertia) {
  const Mat3 R = q.toRotationMatrix();
  return R * inv_inertia.asDiagonal() * R.transpose();
}

struct BodyHandle {
  Vec3* position = nullptr;           // centre (nullptr: the world)
  Quat* orientation = nullptr;        // nullptr for particles and the world
  Real inv_mass = 0;                  // 1/kg
  Vec3 inv_inertia = Vec3::Zero();    // principal, 1/(kg m^2)

  bool is_world() const { return position == nullptr; }
  bool rotates() const { return orientation != nullptr && inv_inertia != Vec3::Zero(); }

  /// I^-1 v for a world-space v.
  Vec3 apply_inv_inertia(const Vec3& v) const {
    return rotates() ? apply_principal_inverse_inertia(*orientation, inv_inertia, v) : Vec3::Zero();
  }
  /// Generalised inverse mass for a push along unit n at world offset r.
  Real positional_weight(const Vec3& r, const Vec3& n) const {
    if (is_world()) return 0;
    const Vec3 rn = r.cross(n);
    return inv_mass + (rotates() ? rn.dot(apply_inv_inertia(rn)) : 0);
  }
  /// World inverse inertia R diag(I^-1) R^T (zero for particles and the world).
  Mat3 world_inv_inertia() const {
    return rotates() ? world_inverse_inertia(*orientation, inv_inertia) : Mat3::Zero();
  }
  /// Effective inverse mass of a point at world offset r: 1/m I - [r]x I^-1 [r]x (3 x 3).
  Mat3 point_inverse_mass(const Vec3& r) const {
    if (is_world()) return Mat3::Zero();
    const Mat3 rx = cross_matrix(r);
    return inv_mass * Mat3::Identity() - rx * world_inv_inertia() * rx;
  }
  /// Generalised inverse mass for a rotation about unit n.
  Real angular_weight(const Vec3& n) const { return rotates() ? n.dot(apply_inv_inertia(n)) : 0; }

  /// Applies positional impulse p at world offset r (position level).
  void apply_position_impulse(const Vec3& p, const Vec3& r) const {
    if (is_world()) return;
    *position += inv_mass * p;
    if (rotates()) rotate_by(apply_inv_inertia(r.cross(p)));
  }
  /// Applies an angular position-level impulse (a rotation vector before I^-1).
  void apply_angular_impulse(const Vec3& p) const {
    if (rotates()) rotate_by(apply_inv_inertia(p));
  }
  /// q += 1/2 [phi, 0] q, normalised.
  void rotate_by(const Vec3& phi) const {
    Quat& q = *orientation;
    const Quat dq = Quat(0, phi.x(), phi.y(), phi.z()) * q;
    q.coeffs() += 0.5 * dq.coeffs();
    q.normalize();
  }
};

/// A particle (a body without rotation) at position x with inverse mass w.
inline BodyHandle particle_handle(Vec3& x, Real w) { return {&x, nullptr, w, Vec3::Zero()}; }

/// One XPBD positional correction C = c along n between two handles (see the file comment);
/// returns dlambda. `lambda` accumulates over the substep's iterations.
inline Real apply_positional_correction(const BodyHandle& a, const BodyHandle& b, const Vec3& n, Real c,
                                        const Vec3& ra, const Vec3& rb, Real alpha_tilde, Real& lambda) {
  const Real w = a.positional_weight(ra, n) + b.positional_weight(rb, n);
  if (w + alpha_tilde <= 0) return 0;
  const Real dlambda = (-c - alpha_tilde * lambda) / (w + alpha_tilde);
  lambda += dlambda;
  const Vec3 p = dlambda * n;
  a.apply_position_impulse(p, ra);
  b.apply_position_impulse(-p, rb);
  return dlambda;
}

/// One XPBD angular correction by angle theta about unit n (a's rotation minus b's).
inline Real apply_angular_correction(const BodyHandle& a, const BodyHandle& b, const Vec3& n, Real theta,
                                     Real alpha_tilde, Real& lambda) {
  const Real w = a.angular_weight(n) + b.angular_weight(n);
  if (w + alpha_tilde <= 0) return 0;
  const Real dlambda = (-theta - alpha_tilde * lambda) / (w + alpha_tilde);
  lambda += dlambda;
  const Vec3 p = dlambda * n;
  a.apply_angular_impulse(p);
  b.apply_angular_impulse(-p);
  return dlambda;
}

/// Point attachment C = e (a's point minus b's, 3 rows) solved as one block:
/// dlambda = -(K_a + K_b + alpha~ I)^-1 (e + alpha~ lambda), K the point inverse masses. One
/// correction along e/|e| (Mueller 2020, eq. 4 with n = e/|e|) converges slowly when the effective
/// mass is anisotropic: a heavy ball far from its anchor turns instead of moving, and a pendulum of
/// that kind stretched by 1 % at 20 substeps.
/// With a basis P (3 x Rows) only the rows e . P are corrected (a prismatic joint's two sideways
/// directions).
template <int Rows = 3>
inline void apply_point_correction(const BodyHandle& a, const BodyHandle& b, const Vec3& e, const Vec3& ra,
                                   const Vec3& rb, Real alpha_tilde, Vec3& lambda,
                                   const Eigen::Matrix<Real, 3, Rows>& basis = Mat3::Identity()) {
  using Block = Eigen::Matrix<Real, Rows, Rows>;
  const Block K = basis.transpose() * (a.point_inverse_mass(ra) + b.point_inverse_mass(rb)) * basis +
                  alpha_tilde * Block::Identity();
  if (K.determinant() <= 1e-300) return;
  const Eigen::Matrix<Real, Rows, 1> dl = K.ldlt().solve(-basis.transpose() * (e + alpha_tilde * lambda));
  const Vec3 p = basis * dl;
  lambda += p;
  a.apply_position_impulse(p, ra);
  b.apply_position_impulse(-p, rb);
}

/// Relative rotation C = e (3 rows, or only the rows in the columns of `basis`) as one block:
/// dlambda = -(P^T (I_a^-1 + I_b^-1) P + alpha~)^-1 P^T (e + alpha~ lambda), p = P dlambda.
template <int Rows>
inline void apply_rotation_correction(const BodyHandle& a, const BodyHandle& b, const Vec3& e,
                                      const Eigen::Matrix<Real, 3, Rows>& basis, Real alpha_tilde, Vec3& lambda) {
  using Block = Eigen::Matrix<Real, Rows, Rows>;
  const Block K = basis.transpose() * (a.world_inv_inertia() + b.world_inv_inertia()) * basis +
                  alpha_tilde * Block::Identity();
  if (K.determinant() <= 1e-300) return;
  const Eigen::Matrix<Real, Rows, 1> dl = K.ldlt().solve(-basis.transpose() * (e + alpha_tilde * lambda));
  const Vec3 p = basis * dl;
  lambda += p;
  a.apply_angular_impulse(p);
  b.apply_angular_impulse(-p);
}

/// Velocity-level handle: the same body seen through its velocities (the velocity pass).
struct BodyVelocityHandle {
  Vec3* velocity = nullptr;
  Vec3* angular_velocity = nullptr;   // nullptr for particles and the world
  const Quat* orientation = nullptr;
  Real inv_mass = 0;
  Vec3 inv_inertia = Vec3::Zero();

  bool rotates() const { return angular_velocity != nullptr && inv_inertia != Vec3::Zero(); }
  Vec3 apply_inv_inertia(const Vec3& v) const {
    return rotates() ? apply_principal_inverse_inertia(*orientation, inv_inertia, v) : Vec3::Zero();
  }
  Mat3 world_inv_inertia() const {
    return rotates() ? world_inverse_inertia(*orientation, inv_inertia) : Mat3::Zero();
  }
  Real weight(const Vec3& r, const Vec3& n) const {
    if (velocity == nullptr) return 0;
    const Vec3 rn = r.cross(n);
    return inv_mass + (rotates() ? rn.dot(apply_inv_inertia(rn)) : 0);
  }
  /// Velocity of the material point at world offset r.
  Vec3 point_velocity(const Vec3& r) const {
    if (velocity == nullptr) return Vec3::Zero();
    return angular_velocity ? Vec3(*velocity + angular_velocity->cross(r)) : *velocity;
  }
  void apply_impulse(const Vec3& p, const Vec3& r) const {
    if (velocity == nullptr) return;
    *velocity += inv_mass * p;
    if (rotates()) *angular_velocity += apply_inv_inertia(r.cross(p));
  }
};

/// A particle seen through its velocity v, inverse mass w.
inline BodyVelocityHandle particle_velocity_handle(Vec3& v, Real w) { return {&v, nullptr, nullptr, w, Vec3::Zero()}; }

/// Applies velocity change dv of the relative velocity (a minus b) at offsets ra, rb as the impulse
/// p = dv / (w_a + w_b) (Mueller 2020, eq. 33).
inline void apply_relative_velocity_change(const BodyVelocityHandle& a, const BodyVelocityHandle& b, const Vec3& dv,
                                           const Vec3& ra, const Vec3& rb) {
  const Real len = dv.norm();
  if (len <= 0) return;
  const Vec3 n = dv / len;
  const Real w = a.weight(ra, n) + b.weight(rb, n);
  if (w <= 0) return;
  const Vec3 p = dv / w;
  a.apply_impulse(p, ra);
  b.apply_impulse(-p, rb);
}

}  // namespace moreau

namespace moreau {

inline BodyHandle rigid_body_handle(const RigidBodyModel& m, RigidBodyState& s, Index b) {
  return {&s.position[b], &s.orientation[b], m.body_inv_mass[b], m.body_inv_inertia[b]};
}

inline BodyVelocityHandle rigid_body_velocity_handle(const RigidBodyModel& m, RigidBodyState& s, Index b) {
  return {&s.velocity[b], &s.angular_velocity[b], &s.orientation[b], m.body_inv_mass[b], m.body_inv_inertia[b]};
}

}  // namespace moreau
