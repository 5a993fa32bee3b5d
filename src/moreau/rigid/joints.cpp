#include "moreau/rigid/joints.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"
#include "moreau/rigid/joint_frames.hpp"

namespace moreau {

namespace {

// A joint end seen through the live state: its handle and its attachment frame in the world.
struct EndView {
  BodyHandle handle;
  const JointEnd* end;

  Vec3 center() const { return handle.is_world() ? Vec3::Zero() : *handle.position; }
  Quat orientation() const { return handle.orientation ? *handle.orientation : Quat::Identity(); }
  Vec3 anchor() const { return center() + orientation() * end->anchor; }
  Quat frame() const { return orientation() * end->frame; }
  Vec3 axis(int k) const { return frame() * Vec3::Unit(k); }
};

EndView end_view(const Model& model, State& state, const JointEnd& e) {
  switch (e.kind) {
    case JointEndKind::world: return {BodyHandle{}, &e};
    case JointEndKind::body: return {rigid_body_handle(model.rigid, state.rigid, e.index), &e};
    case JointEndKind::particle:
      return {particle_handle(state.position[e.index], model.particle_inv_mass[e.index]), &e};
  }
  return {BodyHandle{}, &e};
}

BodyVelocityHandle velocity_view(const Model& model, State& state, const JointEnd& e) {
  switch (e.kind) {
    case JointEndKind::world: return {};
    case JointEndKind::body: return rigid_body_velocity_handle(model.rigid, state.rigid, e.index);
    case JointEndKind::particle:
      return particle_velocity_handle(state.velocity[e.index], model.particle_inv_mass[e.index]);
  }
  return {};
}

// Signed angle from u to v about unit axis n.
Real signed_angle(const Vec3& u, const Vec3& v, const Vec3& n) { return std::atan2(u.cross(v).dot(n), u.dot(v)); }

// Positional correction by the vector e (C grows when a moves along e).
void correct_position(const EndView& a, const EndView& b, const Vec3& e, Real alpha_tilde, Real& lambda) {
  const Real c = e.norm();
  if (c <= 0) return;
  apply_positional_correction(a.handle, b.handle, e / c, c, a.anchor() - a.center(), b.anchor() - b.center(),
                              alpha_tilde, lambda);
}

// Angular correction by the rotation vector e (C grows when a rotates about e).
void correct_rotation(const EndView& a, const EndView& b, const Vec3& e, Real alpha_tilde, Real& lambda) {
  const Real c = e.norm();
  if (c <= 0) return;
  apply_angular_correction(a.handle, b.handle, e / c, c, alpha_tilde, lambda);
}

// Clamps the accumulated multiplier so that |lambda| / h^2 stays below max (0 = no limit), undoing
// the excess of the last correction along the same direction.
Real limited(Real lambda, Real max, Real h) {
  if (max <= 0) return lambda;
  const Real bound = max * h * h;
  return std::clamp(lambda, -bound, bound);
}

Real hinge_angle(const Vec3& axis_a, const Vec3& y_a, const Vec3& y_b) { return signed_angle(y_a, y_b, axis_a); }

// Twist of a spherical joint: the angle between the two ends' y axes about the mean of their x
// axes, n = (x_a + x_b)/|x_a + x_b|, after projecting both onto the plane normal to n. Returns false
// where it is undefined (the x axes opposite, or a y axis along n).
struct Twist {
  Vec3 axis;
  Real angle = 0;
};
bool spherical_twist(const Vec3& xa, const Vec3& ya, const Vec3& xb, const Vec3& yb, Twist& out) {
  const Vec3 mean = xa + xb;
  if (mean.norm() <= 1e-9) return false;
  const Vec3 n = mean.normalized();
  const Vec3 pa = ya - n.dot(ya) * n, pb = yb - n.dot(yb) * n;
  if (pa.norm() <= 1e-9 || pb.norm() <= 1e-9) return false;
  out = {n, signed_angle(pa.normalized(), pb.normalized(), n)};
  return true;
}

// The drive's angular correction, limited in torque: solved as a correction with its own
// multiplier; when the limit binds, the correction is scaled back to the allowed multiplier.
void drive_rotation(const EndView& a, const EndView& b, const Vec3& n, Real error, const Joint& j, Real h,
                    Real& lambda) {
  const Real alpha_tilde = j.drive_compliance / (h * h);
  const Real w = a.handle.angular_weight(n) + b.handle.angular_weight(n);
  if (w + alpha_tilde <= 0) return;
  Real dlambda = (-error - alpha_tilde * lambda) / (w + alpha_tilde);
  dlambda = limited(lambda + dlambda, j.drive_max, h) - lambda;
  lambda += dlambda;
  a.handle.apply_angular_impulse(dlambda * n);
  b.handle.apply_angular_impulse(-dlambda * n);
}

void drive_position(const EndView& a, const EndView& b, const Vec3& n, Real error, const Joint& j, Real h,
                    Real& lambda) {
  const Real alpha_tilde = j.drive_compliance / (h * h);
  const Vec3 ra = a.anchor() - a.center(), rb = b.anchor() - b.center();
  const Real w = a.handle.positional_weight(ra, n) + b.handle.positional_weight(rb, n);
  if (w + alpha_tilde <= 0) return;
  Real dlambda = (-error - alpha_tilde * lambda) / (w + alpha_tilde);
  dlambda = limited(lambda + dlambda, j.drive_max, h) - lambda;
  lambda += dlambda;
  a.handle.apply_position_impulse(dlambda * n, ra);
  b.handle.apply_position_impulse(-dlambda * n, rb);
}

}  // namespace

void reset_joints(const Model& model, State& state) {
  const Index n = static_cast<Index>(model.joints.size());
  for (Index k = 0; k < n; ++k) {
    state.joint_lambda[k] = JointLambdas{};
    state.joint_drive_start[k] = joint_coordinate(model, state, k);
  }
}

void project_joints(const Model& model, State& state, Real h) {
  const Real inv_h2 = 1 / (h * h);
  for (size_t k = 0; k < model.joints.size(); ++k) {
    const Joint& j = model.joints[k];
    JointLambdas& L = state.joint_lambda[k];
    const EndView a = end_view(model, state, j.ends[0]), b = end_view(model, state, j.ends[1]);
    const Real alpha = j.compliance * inv_h2, alpha_angular = j.angular_compliance * inv_h2;
    const bool direct = model.joint_forest.in_tree(k);  // equality rows already solved (joint_tree.hpp)

    // Orientation parts first (they move the anchors), then the positional part.
    switch (j.type) {
      case JointType::fixed:
      case JointType::prismatic:
        if (direct) break;
        apply_rotation_correction<3>(a.handle, b.handle, orientation_error(a.frame(), b.frame()), Mat3::Identity(),
                                     alpha_angular, L.orientation);
        break;
      case JointType::hinge: {
        Eigen::Matrix<Real, 3, 2> across;
        across << a.axis(1), a.axis(2);
        if (!direct)
          apply_rotation_correction<2>(a.handle, b.handle, b.axis(0).cross(a.axis(0)), across, alpha_angular,
                                       L.orientation);
        const Vec3 axis = a.axis(0);
        const Real phi = hinge_angle(axis, a.axis(1), b.axis(1));
        if (j.limited && (phi < j.lower || phi > j.upper)) {
          const Real target = std::clamp(phi, j.lower, j.upper);
          correct_rotation(a, b, -axis * (phi - target), 0, L.limit);
        }
        if (j.drive != DriveMode::none) {
          Real target = j.drive == DriveMode::position ? j.drive_target
                                                       : state.joint_drive_start[k] + h * j.drive_target;
          if (j.limited) target = std::clamp(target, j.lower, j.upper);
          // Wrap the error into (-pi, pi] so a target across the seam turns the short way.
          const Real error = std::remainder(hinge_angle(axis, a.axis(1), b.axis(1)) - target, 2 * kPi);
          drive_rotation(a, b, -axis, error, j, h, L.drive);
        }
        break;
      }
      case JointType::spherical: {
        if (j.swing_limited) {
          const Vec3 xa = a.axis(0), xb = b.axis(0);
          const Vec3 k_axis = xa.cross(xb);
          const Real swing = std::atan2(k_axis.norm(), xa.dot(xb));
          if (swing > j.swing && k_axis.norm() > 1e-12)
            correct_rotation(a, b, -k_axis.normalized() * (swing - j.swing), 0, L.swing);
        }
        Twist t;
        if (j.twist_limited && spherical_twist(a.axis(0), a.axis(1), b.axis(0), b.axis(1), t) &&
            (t.angle < j.twist_lower || t.angle > j.twist_upper)) {
          const Real target = std::clamp(t.angle, j.twist_lower, j.twist_upper);
          correct_rotation(a, b, -t.axis * (t.angle - target), 0, L.twist);
        }
        break;
      }
      case JointType::distance: break;
    }

    const Vec3 d = a.anchor() - b.anchor();
    switch (j.type) {
      case JointType::fixed:
      case JointType::hinge:
      case JointType::spherical:
        if (direct) break;
        apply_point_correction(a.handle, b.handle, d, a.anchor() - a.center(), b.anchor() - b.center(), alpha,
                               L.position);
        break;
      case JointType::prismatic: {
        const Vec3 x = a.axis(0);
        Eigen::Matrix<Real, 3, 2> across;
        across << a.axis(1), a.axis(2);
        apply_point_correction<2>(a.handle, b.handle, d, a.anchor() - a.center(), b.anchor() - b.center(), alpha,
                                  L.position, across);
        const Real along = (a.anchor() - b.anchor()).dot(x), slide = -along;
        if (j.limited && (slide < j.lower || slide > j.upper))
          correct_position(a, b, x * (along + std::clamp(slide, j.lower, j.upper)), alpha, L.distance);
        if (j.drive != DriveMode::none) {
          Real target = j.drive == DriveMode::position ? j.drive_target
                                                       : state.joint_drive_start[k] + h * j.drive_target;
          if (j.limited) target = std::clamp(target, j.lower, j.upper);
          const Real now = -(a.anchor() - b.anchor()).dot(a.axis(0));
          drive_position(a, b, -a.axis(0), now - target, j, h, L.drive);
        }
        break;
      }
      case JointType::distance: {
        const Real len = d.norm();
        if (len <= 0 || direct) break;
        const Real target = std::clamp(len, j.lower, j.upper);
        if (len != target) correct_position(a, b, d / len * (len - target), alpha, L.distance);
        break;
      }
    }
  }
}

void damp_joints(const Model& model, State& state, Real h) {
  for (const Joint& j : model.joints) {
    if (j.damping <= 0 && j.angular_damping <= 0) continue;
    const BodyVelocityHandle va = velocity_view(model, state, j.ends[0]), vb = velocity_view(model, state, j.ends[1]);
    const ConstEndView a = const_end_view(state, j.ends[0]), b = const_end_view(state, j.ends[1]);
    const Vec3 ra = a.anchor() - a.center, rb = b.anchor() - b.center;
    if (j.damping > 0) {
      const Vec3 dv = va.point_velocity(ra) - vb.point_velocity(rb);
      apply_relative_velocity_change(va, vb, -dv * std::min(j.damping * h, Real(1)), ra, rb);
    }
    if (j.angular_damping > 0 && (va.rotates() || vb.rotates())) {
      const Vec3 wa = va.angular_velocity ? *va.angular_velocity : Vec3::Zero();
      const Vec3 wb = vb.angular_velocity ? *vb.angular_velocity : Vec3::Zero();
      const Vec3 dw = -(wa - wb) * std::min(j.angular_damping * h, Real(1));
      const Real len = dw.norm();
      if (len <= 0) continue;
      const Vec3 n = dw / len;
      const Real w = n.dot(va.apply_inv_inertia(n)) + n.dot(vb.apply_inv_inertia(n));
      if (w <= 0) continue;
      const Vec3 p = dw / w;
      if (va.rotates()) *va.angular_velocity += va.apply_inv_inertia(p);
      if (vb.rotates()) *vb.angular_velocity -= vb.apply_inv_inertia(p);
    }
  }
}

JointError joint_error(const Model& model, const State& state, Index k) {
  const Joint& j = model.joints[k];
  const ConstEndView a = const_end_view(state, j.ends[0]), b = const_end_view(state, j.ends[1]);
  const Vec3 d = a.anchor() - b.anchor();
  JointError e;
  auto excess = [](Real v, Real lo, Real hi) { return v < lo ? lo - v : v > hi ? v - hi : Real(0); };
  switch (j.type) {
    case JointType::fixed:
      e.position = d.norm();
      e.angle = orientation_error(a.frame(), b.frame()).norm();
      break;
    case JointType::spherical: {
      e.position = d.norm();
      const Vec3 xa = a.axis(0), xb = b.axis(0);
      if (j.swing_limited) e.angle = std::max(Real(0), std::atan2(xa.cross(xb).norm(), xa.dot(xb)) - j.swing);
      Twist t;
      if (j.twist_limited && spherical_twist(xa, a.axis(1), xb, b.axis(1), t))
        e.angle = std::max(e.angle, excess(t.angle, j.twist_lower, j.twist_upper));
      break;
    }
    case JointType::hinge: {
      e.position = d.norm();
      e.angle = std::asin(std::min(Real(1), a.axis(0).cross(b.axis(0)).norm()));
      if (j.limited) e.angle = std::max(e.angle, excess(hinge_angle(a.axis(0), a.axis(1), b.axis(1)), j.lower, j.upper));
      break;
    }
    case JointType::prismatic: {
      const Vec3 x = a.axis(0);
      e.position = (d - d.dot(x) * x).norm();
      if (j.limited) e.position = std::max(e.position, excess(-d.dot(x), j.lower, j.upper));
      e.angle = orientation_error(a.frame(), b.frame()).norm();
      break;
    }
    case JointType::distance: e.position = excess(d.norm(), j.lower, j.upper); break;
  }
  return e;
}

Real joint_coordinate(const Model& model, const State& state, Index k) {
  const Joint& j = model.joints[k];
  const ConstEndView a = const_end_view(state, j.ends[0]), b = const_end_view(state, j.ends[1]);
  if (j.type == JointType::hinge) return hinge_angle(a.axis(0), a.axis(1), b.axis(1));
  if (j.type == JointType::prismatic) return -(a.anchor() - b.anchor()).dot(a.axis(0));
  return 0;
}

}  // namespace moreau
