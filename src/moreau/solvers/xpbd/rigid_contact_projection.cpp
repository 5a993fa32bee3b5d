#include "moreau/solvers/xpbd/rigid_contact_projection.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"
#include "moreau/rigid/rigid_motion.hpp"
#include "moreau/solvers/xpbd/contact_blocks.hpp"

namespace moreau {

namespace {

template <class Handle>
InverseMass inverse_mass(const Handle& h) {
  return {h.inv_mass, h.world_inv_inertia()};
}

// The net impulse of a manifold's rows on one body: sum p_r and sum r_r x p_r.
struct NetImpulse {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
  void add(const Vec3& p, const Vec3& r) {
    linear += p;
    angular += r.cross(p);
  }
};

// Solves one manifold's position block and applies its impulses:
// x += p / m, q += 1/2 [I^-1 (r x p), 0] q with the world inverse inertia of the solve.
void project_manifold(RigidManifold& mf, RigidContactPoint* points, const BodyHandle& ha, const BodyHandle& hb,
                      const RigidBodyState& s, const SubstepStart& start) {
  const ContactRows rows = manifold_rows(mf, points, s, start);
  if (rows.points == 0) {
    mf.sliding = false;
    return;
  }
  const int n = rows.size();
  const InverseMass ma = inverse_mass(ha), mb = inverse_mass(hb);
  const BlockMatrix K = effective_mass_block(ma, mb, rows);
  const PositionBlockSolution solution = solve_position_block(rows, K);
  const RowValues& x = solution.x;
  mf.sliding = solution.sliding;
  for (int j = 0; j < rows.points; ++j) {
    RigidContactPoint& c = points[rows.point[j]];
    if (x[3 * j] <= 0) continue;
    c.lambda_normal += x[3 * j];
    c.touching = true;
  }
  NetImpulse pa_net, pb_net;
  for (int r = 0; r < n; ++r)
    if (x[r] != 0) {
      pa_net.add(x[r] * rows.direction[r], rows.offset_a[r]);
      pb_net.add(-x[r] * rows.direction[r], rows.offset_b[r]);
    }
  if (!ha.is_world()) {
    *ha.position += ma.linear * pa_net.linear;
    if (ha.rotates()) ha.rotate_by(ma.angular * pa_net.angular);
  }
  if (!hb.is_world()) {
    *hb.position += mb.linear * pb_net.linear;
    if (hb.rotates()) hb.rotate_by(mb.angular * pb_net.angular);
  }
}

}  // namespace

void reset_rigid_contacts(State& state) {
  for (RigidManifold& mf : state.rigid_contacts.manifolds) mf.touching = false;
  for (RigidContactPoint& c : state.rigid_contacts.points) {
    c.lambda_normal = 0;
    c.lambda_tangent = Vec2::Zero();
    c.touching = false;
  }
}

void project_rigid_contacts(const Model& model, State& state, const SubstepStart& start) {
  const RigidBodyModel& m = model.rigid;
  RigidBodyState& s = state.rigid;
  RigidContacts& contacts = state.rigid_contacts;
  for (RigidManifold& mf : contacts.manifolds) {
    if (mf.with_joints) continue;  // solved with the joints (tree_contacts.hpp)
    const BodyHandle ha = rigid_body_handle(m, s, mf.body_a), hb = rigid_body_handle(m, s, mf.body_b);
    RigidContactPoint* points = contacts.points.data() + mf.first;
    project_manifold(mf, points, ha, hb, s, start);
    for (Index i = 0; i < mf.count; ++i) mf.touching |= points[i].touching;
  }
}

void accumulate_stuck_slip(State& state, const SubstepStart& start) {
  const RigidBodyState& s = state.rigid;
  RigidContacts& contacts = state.rigid_contacts;
  for (RigidManifold& mf : contacts.manifolds) {
    const Pose pa{s.position[mf.body_a], s.orientation[mf.body_a]}, pb{s.position[mf.body_b], s.orientation[mf.body_b]};
    const Pose sa = start.body_pose(mf.body_a), sb = start.body_pose(mf.body_b);
    for (Index i = mf.first; i < mf.first + mf.count; ++i) {
      RigidContactPoint& c = contacts.points[i];
      if (mf.sliding || !c.touching) {
        c.stuck_slip = Vec3::Zero();
        continue;
      }
      const Vec3 slip = (pa.to_world(c.material_a) - sa.to_world(c.material_a)) -
                        (pb.to_world(c.material_b) - sb.to_world(c.material_b)) + c.stuck_slip;
      c.stuck_slip = slip - slip.dot(c.normal) * c.normal;
    }
  }
}

void rigid_contact_velocities(const Model& model, State& state, const RigidSubstepStart& before_solve, Real h) {
  const RigidBodyModel& m = model.rigid;
  RigidBodyState& s = state.rigid;
  RigidContacts& contacts = state.rigid_contacts;
  const Real resting_speed = 2 * model.settings.gravity.norm() * h;
  for (RigidManifold& mf : contacts.manifolds) {
    if (!mf.touching) continue;
    const Index a = mf.body_a, b = mf.body_b;
    const BodyVelocityHandle va = rigid_body_velocity_handle(m, s, a), vb = rigid_body_velocity_handle(m, s, b);
    // Rows of the touching points: normal (restitution) and two tangents (dynamic friction), in the
    // directions the last projection used.
    RowValues target{}, bound{};
    ContactRows rows;
    for (Index i = mf.first; i < mf.first + mf.count; ++i) {
      const RigidContactPoint& c = contacts.points[i];
      if (!c.touching) continue;
      const int r0 = rows.size();
      const Vec3& n = c.normal;
      const Vec3 v = va.point_velocity(c.offset_a) - vb.point_velocity(c.offset_b);
      const Vec3 before = (before_solve.velocity[a] + before_solve.angular_velocity[a].cross(c.offset_a)) -
                          (before_solve.velocity[b] + before_solve.angular_velocity[b].cross(c.offset_b));
      const Real restitution = std::abs(n.dot(v)) <= resting_speed ? 0 : mf.restitution;
      const Vec3 t1 = contact_tangent(n);
      rows.direction[r0] = n;
      rows.direction[r0 + 1] = t1;
      rows.direction[r0 + 2] = n.cross(t1);
      // The approach speed is the larger of the one before the solve (Mueller 2020) and the one now:
      // in a row of touching balls the inner contacts were at rest before the solve and are
      // approached only once the manifolds before them in this pass have bounced (Newton's cradle).
      target[r0] = std::max(-restitution * std::min(n.dot(before), n.dot(v)), Real(0));
      bound[r0] = mf.dynamic_friction * c.lambda_normal / h;  // friction impulse limit of this point
      for (int r = r0; r < r0 + 3; ++r) {
        rows.offset_a[r] = c.offset_a;
        rows.offset_b[r] = c.offset_b;
      }
      rows.point[rows.points++] = static_cast<int>(i - mf.first);
    }
    // Effective masses and the projected Gauss-Seidel solve of
    //   v_n -> target (restitution, Mueller 2020 eq. 34), v_t -> 0 with |p_t| <= mu_k lambda_n / h.
    const int n = rows.size();
    const InverseMass ma = inverse_mass(va), mb = inverse_mass(vb);
    const BlockMatrix K = effective_mass_block(ma, mb, rows);
    RowValues v0{};
    Real speed = 0;
    for (int r = 0; r < n; ++r) {
      v0[r] = rows.direction[r].dot(va.point_velocity(rows.offset_a[r]) - vb.point_velocity(rows.offset_b[r]));
      speed = std::max({speed, std::abs(v0[r]), target[r]});
    }
    const RowValues x = solve_velocity_block(K, v0, target, bound, n, speed);
    NetImpulse pa_net, pb_net;
    for (int r = 0; r < n; ++r)
      if (x[r] != 0) {
        pa_net.add(x[r] * rows.direction[r], rows.offset_a[r]);
        pb_net.add(-x[r] * rows.direction[r], rows.offset_b[r]);
      }
    if (va.velocity) {
      *va.velocity += ma.linear * pa_net.linear;
      if (va.rotates()) *va.angular_velocity += ma.angular * pa_net.angular;
    }
    if (vb.velocity) {
      *vb.velocity += mb.linear * pb_net.linear;
      if (vb.rotates()) *vb.angular_velocity += mb.angular * pb_net.angular;
    }
  }
}

}  // namespace moreau
