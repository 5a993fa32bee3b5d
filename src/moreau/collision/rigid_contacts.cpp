#include "moreau/collision/rigid_contacts.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"

namespace moreau {

namespace {

Pose body_pose(const RigidBodyState& s, Index b) { return {s.position[b], s.orientation[b]}; }
// World bounds of body b grown by its margin; planes are unbounded.
void body_bounds(const RigidBodyModel& m, const RigidBodyState& s, Index b, Real margin, Vec3& lo, Vec3& hi) {
  const Shape& shape = m.body_shape[b];
  if (shape.type == ShapeType::plane) {
    lo = Vec3::Constant(-1e300);
    hi = Vec3::Constant(1e300);
    return;
  }
  const Mat3 R = s.orientation[b].toRotationMatrix();
  const Vec3 e = R.cwiseAbs() * shape.local_half_extents() + Vec3::Constant(margin);
  lo = s.position[b] - e;
  hi = s.position[b] + e;
}

// Carries stuck slip (of a manifold that did not slide) and the row impulses over from last
// step's point of the same pair with the same body-frame cores (within 5 % of the smaller body's
// size: the same corner or face point, not a neighbour). A pair with a mesh has a manifold per
// triangle; all of the pair's previous manifolds are searched.
void carry_contact_memory(const RigidBodyModel& m, RigidContacts& contacts) {
  const RigidBroadPhaseScratch& bp = contacts.scratch;
  const auto& previous = bp.previous_manifolds;
  size_t begin = 0;
  for (RigidManifold& mf : contacts.manifolds) {
    const auto pair = std::make_pair(mf.body_a, mf.body_b);
    while (begin < previous.size() && std::make_pair(previous[begin].body_a, previous[begin].body_b) < pair) ++begin;
    if (begin == previous.size()) return;
    Real size = std::numeric_limits<Real>::infinity();
    for (Index body : {mf.body_a, mf.body_b}) size = std::min(size, m.body_shape[body].bounding_radius());
    const Real tolerance = 0.05 * size;
    for (size_t old = begin; old < previous.size() && previous[old].body_a == mf.body_a && previous[old].body_b == mf.body_b;
         ++old) {
      const RigidManifold& before = previous[old];
      for (Index i = mf.first; i < mf.first + mf.count; ++i) {
        RigidContactPoint& c = contacts.points[i];
        for (Index j = before.first; j < before.first + before.count; ++j) {
          const RigidContactPoint& p = bp.previous_points[j];
          if ((p.geometry.core_a - c.geometry.core_a).norm() + (p.geometry.core_b - c.geometry.core_b).norm() <
              tolerance) {
            if (!before.sliding) c.stuck_slip = p.stuck_slip;
            c.row_impulse = p.row_impulse;
            break;
          }
        }
      }
    }
  }
}

// Pairs of bodies a joint keeps from colliding.
bool joined(const RigidBodyModel& m, Index a, Index b) {
  const std::vector<Index>& group = m.body_contact_group;  // may stop short of the bodies added after a rod
  const Index groups = static_cast<Index>(group.size());
  if (a < groups && b < groups && group[a] >= 0 && group[a] == group[b]) return true;
  const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
  return std::binary_search(m.pairs_without_contact.begin(), m.pairs_without_contact.end(), key);
}

}  // namespace

void detect_rigid_contacts(const Model& model, State& state, int threads) {
  const RigidBodyModel& m = model.rigid;
  RigidBodyState& s = state.rigid;
  RigidContacts& contacts = state.rigid_contacts;
  RigidBroadPhaseScratch& bp = contacts.scratch;
  std::swap(bp.previous_manifolds, contacts.manifolds);
  std::swap(bp.previous_points, contacts.points);
  contacts.points.clear();
  contacts.manifolds.clear();
  const Index n = m.count();
  if (n == 0) return;
  const Real dt = model.settings.dt, k = model.settings.contact_margin_factor;
  const Real fall = dt * dt * model.settings.gravity.norm();
  const Real slop_fraction = 0.01;

  // Margin: how far a body may travel in the step (k dt |v| plus the fall under gravity, so resting
  // contacts are never missed) plus a slop of 1 % of its size.
  bp.lower.resize(n);
  bp.upper.resize(n);
  bp.margin.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (Index b = 0; b < n; ++b) {
    const Real radius = m.body_shape[b].bounding_radius();
    const Real size = std::isfinite(radius) ? radius : 0;
    bp.margin[b] = k * dt * (s.velocity[b].norm() + s.angular_velocity[b].norm() * size) + k * fall + slop_fraction * size;
    body_bounds(m, s, b, bp.margin[b], bp.lower[b], bp.upper[b]);
  }

  // Sweep and prune along x (a fixed order: determinism).
  bp.order.resize(n);
  for (Index b = 0; b < n; ++b) bp.order[b] = b;
  std::sort(bp.order.begin(), bp.order.end(), [&](Index a, Index b) {
    return bp.lower[a].x() < bp.lower[b].x() || (bp.lower[a].x() == bp.lower[b].x() && a < b);
  });
  // Each body's sweep on its own (threads split the bodies); the finds are merged and sorted, so
  // the pair list does not depend on the thread count.
  const int team = std::max(1, threads);
  bp.thread_pairs.resize(team);
#pragma omp parallel num_threads(team)
  {
    std::vector<std::array<Index, 2>>& found = bp.thread_pairs[omp_get_thread_num()];
    found.clear();
#pragma omp for schedule(dynamic, 64)
    for (Index i = 0; i < n; ++i) {
      const Index a = bp.order[i];
      for (Index j = i + 1; j < n; ++j) {
        const Index b = bp.order[j];
        if (bp.lower[b].x() > bp.upper[a].x()) break;
        if (!m.is_dynamic(a) && !m.is_dynamic(b)) continue;
        if ((bp.lower[a].array() > bp.upper[b].array()).any() || (bp.lower[b].array() > bp.upper[a].array()).any())
          continue;
        if (joined(m, a, b)) continue;
        found.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  }
  bp.pairs.clear();
  for (const auto& found : bp.thread_pairs) bp.pairs.insert(bp.pairs.end(), found.begin(), found.end());
  std::sort(bp.pairs.begin(), bp.pairs.end());

  // Narrow phase per pair (parallel), gathered in pair order.
  auto pair_margin = [&](Index a, Index b) {
    // Against a plane only the approach along its normal can bring a point to it: a box sliding
    // fast along a plane would otherwise take its top corners as contacts (at 60 Hz, k dt |v|
    // exceeds a 0.2 m box above 6 m/s) and be tipped over by them.
    const Index plane = m.body_shape[b].type == ShapeType::plane ? b : m.body_shape[a].type == ShapeType::plane ? a : -1;
    if (plane < 0) return bp.margin[a] + bp.margin[b];
    const Index body = plane == a ? b : a;
    const Vec3 n = s.orientation[plane] * Vec3::UnitY();
    const Real size = m.body_shape[body].bounding_radius();
    const Real approach = std::max(Real(0), (s.velocity[plane] - s.velocity[body]).dot(n));
    return k * dt * (approach + s.angular_velocity[body].norm() * size) + k * fall + slop_fraction * size;
  };
  const Index pairs = static_cast<Index>(bp.pairs.size());
  if (static_cast<Index>(bp.pair_manifolds.size()) < pairs) bp.pair_manifolds.resize(pairs);
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
  for (Index p = 0; p < pairs; ++p) {
    const Index a = bp.pairs[p][0], b = bp.pairs[p][1];
    const Shape &sa = m.body_shape[a], &sb = m.body_shape[b];
    const Real margin = pair_margin(a, b);
    std::vector<ContactManifold>& found = bp.pair_manifolds[p];
    found.clear();
    if (sb.type == ShapeType::triangle_mesh) {
      collide_with_mesh(sa, body_pose(s, a), sb, body_pose(s, b), margin, found);
    } else if (sa.type == ShapeType::triangle_mesh) {
      collide_with_mesh(sb, body_pose(s, b), sa, body_pose(s, a), margin, found);
      for (ContactManifold& cm : found) swap_sides(cm);
    } else {
      const ContactManifold cm = collide_shapes(sa, body_pose(s, a), sb, body_pose(s, b), margin);
      if (cm.count > 0) found.push_back(cm);
    }
  }
  for (Index p = 0; p < pairs; ++p)
    for (const ContactManifold& cm : bp.pair_manifolds[p]) {
      const Index a = bp.pairs[p][0], b = bp.pairs[p][1];
      RigidManifold mf;
      mf.body_a = a;
      mf.body_b = b;
      mf.first = static_cast<Index>(contacts.points.size());
      mf.count = cm.count;
      mf.frame = cm.frame;
      mf.static_friction = 0.5 * (m.body_static_friction[a] + m.body_static_friction[b]);
      mf.dynamic_friction = 0.5 * (m.body_dynamic_friction[a] + m.body_dynamic_friction[b]);
      mf.restitution = 0.5 * (m.body_restitution[a] + m.body_restitution[b]);
      mf.adhesion = std::max(m.body_adhesion[a], m.body_adhesion[b]);
      contacts.manifolds.push_back(mf);
      for (int c = 0; c < cm.count; ++c) {
        RigidContactPoint point;
        point.geometry = cm.points[c];
        contacts.points.push_back(point);
      }
    }
  carry_contact_memory(m, contacts);
}

Index touching_contact_count(const Model& model, const State& state, Index object) {
  Index count = 0;
  const RigidContacts& contacts = state.rigid_contacts;
  for (const RigidManifold& mf : contacts.manifolds) {
    if (object >= 0 && model.rigid.body_object[mf.body_a] != object && model.rigid.body_object[mf.body_b] != object)
      continue;
    for (Index i = mf.first; i < mf.first + mf.count; ++i) count += contacts.points[i].touching ? 1 : 0;
  }
  return count;
}

}  // namespace moreau
