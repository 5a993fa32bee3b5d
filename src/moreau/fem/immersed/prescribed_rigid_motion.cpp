#include "moreau/fem/immersed/prescribed_rigid_motion.hpp"

#include <Eigen/Geometry>

namespace moreau {

namespace {

// Director i (from 0) of a frame laid out as (phi, d_1, .., d_dim), each dim numbers.
Vec3 director(const VectorX& q, int i, int dim) {
  Vec3 d = Vec3::Zero();
  for (int k = 0; k < dim; ++k) d[k] = q[(i + 1) * dim + k];
  return d;
}

void set_director(VectorX& q, int i, int dim, const Vec3& d) {
  for (int k = 0; k < dim; ++k) q[(i + 1) * dim + k] = d[k];
}

}  // namespace

VectorX advance_prescribed_frame(const PrescribedRigidMotion& motion, const VectorX& q, Real t, Real dt, int dim) {
  const Real middle = t + dt / 2;
  const Vec3 v = motion.velocity(middle), turn = dt * motion.angular_velocity(middle);
  const Real angle = turn.norm();
  const Mat3 rotation = angle > 0 ? Mat3(Eigen::AngleAxis<Real>(angle, turn / angle)) : Mat3::Identity();
  VectorX next = q;
  for (int k = 0; k < dim; ++k) next[k] += dt * v[k];
  for (int i = 0; i < dim; ++i) set_director(next, i, dim, rotation * director(q, i, dim));
  return next;
}

VectorX prescribed_frame_velocity(const PrescribedRigidMotion& motion, const VectorX& q, Real t, int dim) {
  const Vec3 v = motion.velocity(t), w = motion.angular_velocity(t);
  VectorX dq = VectorX::Zero(q.size());
  for (int k = 0; k < dim; ++k) dq[k] = v[k];
  for (int i = 0; i < dim; ++i) set_director(dq, i, dim, w.cross(director(q, i, dim)));
  return dq;
}

}  // namespace moreau
