#pragma once
// A joint end's pose and attachment frame in the world, read from a state, and the angles the
// joint types measure between two frames.
#include <cmath>

#include "moreau/constraints/joints/joint.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

struct JointEndPose {
  Vec3 center = Vec3::Zero();
  Quat orientation = Quat::Identity();
  const JointEnd* end = nullptr;

  Vec3 anchor() const { return center + orientation * end->anchor; }
  Vec3 offset() const { return anchor() - center; }  // world offset of the anchor from the centre
  Quat frame() const { return orientation * end->frame; }
  Vec3 axis(int k) const { return frame() * Vec3::Unit(k); }
};

inline JointEndPose end_pose(const State& state, const JointEnd& e) {
  JointEndPose v{Vec3::Zero(), Quat::Identity(), &e};
  if (e.kind == BodyEndKind::body) {
    v.center = state.rigid.position[e.index];
    v.orientation = state.rigid.orientation[e.index];
  } else if (e.kind == BodyEndKind::particle) {
    v.center = state.position[e.index];
  }
  return v;
}

/// Rotation vector 2 vec(f_a f_b^-1) of frame a relative to frame b, taken on the short side of
/// the quaternion double cover (zero when the frames coincide).
inline Vec3 orientation_error(const Quat& fa, const Quat& fb) {
  const Quat dq = fa * fb.conjugate();
  const Vec3 e = 2 * dq.vec();
  return dq.w() >= 0 ? e : Vec3(-e);
}

/// Signed angle from u to v about unit axis n.
inline Real signed_angle(const Vec3& u, const Vec3& v, const Vec3& n) {
  return std::atan2(u.cross(v).dot(n), u.dot(v));
}

/// Hinge angle of b relative to a about a's x axis.
inline Real hinge_angle(const JointEndPose& a, const JointEndPose& b) {
  return signed_angle(a.axis(1), b.axis(1), a.axis(0));
}

/// Slide of a prismatic joint: b's anchor relative to a's along a's x axis (m).
inline Real prismatic_slide(const JointEndPose& a, const JointEndPose& b) {
  return -(a.anchor() - b.anchor()).dot(a.axis(0));
}

/// Amount by which v leaves [lo, hi] (0 inside).
inline Real excess(Real v, Real lo, Real hi) { return v < lo ? lo - v : v > hi ? v - hi : Real(0); }

}  // namespace moreau
