#include "moreau/rigid/rigid_motion.hpp"

#include <cmath>

#include "moreau/model/model.hpp"
#include "moreau/rigid/rigid_bodies.hpp"

namespace moreau {

Quat rotate_by_angular_velocity(const Quat& q, const Vec3& w, Real h) {
  const Real angle = w.norm() * h;
  if (angle <= 0) return q;
  return (Quat(Eigen::AngleAxisd(angle, w.normalized())) * q).normalized();
}

Vec3 turn_between(const Quat& from, const Quat& to) {
  Quat dq = to * from.conjugate();
  if (dq.w() < 0) dq.coeffs() = -dq.coeffs();  // the shorter way round
  // dq = (cos(a/2), sin(a/2) u): the rotation vector a u is 2 atan2(|v|, w) v / |v|.
  const Real s = dq.vec().norm();
  const Real scale = s > 1e-12 ? 2 * std::atan2(s, dq.w()) / s : 2 / dq.w();
  return scale * dq.vec();
}

Vec3 gyroscopic_velocity_change(const Quat& q, const Vec3& w_world, const Vec3& inertia, const Vec3& inv_inertia,
                                Real h) {
  const Vec3 w = q.conjugate() * w_world;
  const Vec3 Iw = inertia.cwiseProduct(w);
  return q * Vec3(h * inv_inertia.cwiseProduct(-w.cross(Iw)));
}

void RigidSubstepStart::fit(Index n) {
  const size_t size = static_cast<size_t>(n);
  if (position.size() == size) return;
  position.assign(size, Vec3::Zero());
  orientation.assign(size, Quat::Identity());
  velocity.assign(size, Vec3::Zero());
  angular_velocity.assign(size, Vec3::Zero());
}

void predict_rigid_bodies(const Model& model, RigidBodyState& s, RigidSubstepStart& start, Real h) {
  const RigidBodyModel& m = model.rigid;
  const Vec3 dv = h * model.settings.gravity;
#pragma omp for schedule(static)
  for (Index b = 0; b < m.count(); ++b) {
    start.position[b] = s.position[b];
    start.orientation[b] = s.orientation[b];
    switch (m.body_motion[b]) {
      case BodyMotion::fixed: break;
      case BodyMotion::kinematic:
        s.position[b] += h * s.velocity[b];
        s.orientation[b] = rotate_by_angular_velocity(s.orientation[b], s.angular_velocity[b], h);
        break;
      case BodyMotion::dynamic: {
        s.velocity[b] += dv;
        s.angular_velocity[b] += gyroscopic_velocity_change(s.orientation[b], s.angular_velocity[b], m.body_inertia[b],
                                                            m.body_inv_inertia[b], h);
        s.position[b] += h * s.velocity[b];
        s.orientation[b] = rotate_by_angular_velocity(s.orientation[b], s.angular_velocity[b], h);
        break;
      }
    }
    // The velocities after prediction, before the solve (restitution's vbar).
    start.velocity[b] = s.velocity[b];
    start.angular_velocity[b] = s.angular_velocity[b];
  }
}

void update_rigid_body_velocities(const Model& model, RigidBodyState& s, const RigidSubstepStart& start, Real h) {
  const RigidBodyModel& m = model.rigid;
#pragma omp for schedule(static)
  for (Index b = 0; b < m.count(); ++b) {
    if (!m.is_dynamic(b)) continue;
    s.velocity[b] = (s.position[b] - start.position[b]) / h;
    s.angular_velocity[b] = turn_between(start.orientation[b], s.orientation[b]) / h;
  }
}

}  // namespace moreau
