#pragma once
// A joint end's attachment frame in the world, read from a const state (probes, the direct tree
// solver), and the orientation error between two frames.
#include "moreau/model/state.hpp"
#include "moreau/rigid/joints.hpp"

namespace moreau {

struct ConstEndView {
  Vec3 center = Vec3::Zero();
  Quat orientation = Quat::Identity();
  const JointEnd* end = nullptr;
  Vec3 anchor() const { return center + orientation * end->anchor; }
  Quat frame() const { return orientation * end->frame; }
  Vec3 axis(int k) const { return frame() * Vec3::Unit(k); }
};

inline ConstEndView const_end_view(const State& state, const JointEnd& e) {
  ConstEndView v{Vec3::Zero(), Quat::Identity(), &e};
  if (e.kind == JointEndKind::body) {
    v.center = state.rigid.position[e.index];
    v.orientation = state.rigid.orientation[e.index];
  } else if (e.kind == JointEndKind::particle) {
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

}  // namespace moreau
