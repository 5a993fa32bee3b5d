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
        const Vec3& wn = s.angular_velocity[b];
        Quat& qn = s.orientation[b];
        qn.coeffs() += 0.5 * h * (Quat(0, wn.x(), wn.y(), wn.z()) * qn).coeffs();
        qn.normalize();
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
    const Quat dq = s.orientation[b] * start.orientation[b].conjugate();
    const Vec3 w = 2.0 / h * dq.vec();
    s.angular_velocity[b] = dq.w() >= 0 ? w : Vec3(-w);
  }
}

}  // namespace moreau
