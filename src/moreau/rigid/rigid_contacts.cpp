#include "moreau/rigid/rigid_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"

namespace moreau {

namespace {

constexpr int kMaxPoints = 4;
// Projected Gauss-Seidel on one manifold's block (at most 12 x 12) is swept until a sweep moves
// no row's value by more than kBlockTolerance of the block's scale plus a floor (1e-8 m in the
// position pass, 1e-8 m/s in the velocity pass), or kMaxBlockSweeps sweeps. The block is a convex
// problem, so converged sweeps give the same body motion whatever the order of the rows; three
// fixed sweeps did not: a box sliding down a slope went 4 % too far or 2 % too short depending on
// the slope's direction, and turned. (Converged, the 210-box pyramid costs 15 ms per step
// against 7.7 ms with three sweeps; performance.md.) The cap is a guard, rarely reached: in the
// first 5 s, by no position block and by 7 of 1.07 million velocity blocks of the pyramid and 100
// of 2.2 million of the 1000 boxes (a block then keeps its last sweep's impulses).
constexpr int kFirstSweeps = 3;  // position pass: enough to tell resting from sliding blocks
constexpr int kMaxBlockSweeps = 200;
constexpr Real kBlockTolerance = 1e-9, kPositionFloor = 1e-8, kVelocityFloor = 1e-8;

using RowVectors = std::array<Vec3, 3 * kMaxPoints>;
using BlockMatrix = std::array<std::array<Real, 3 * kMaxPoints>, 3 * kMaxPoints>;

// A body's inverse mass and world inverse inertia, fetched once per manifold (zero for the world,
// fixed and kinematic bodies).
struct InverseMass {
  Real linear = 0;
  Mat3 angular = Mat3::Zero();
};

template <class Handle>
InverseMass inverse_mass(const Handle& h) {
  return {h.inv_mass, h.world_inv_inertia()};
}

// Effective-mass matrix of `rows` contact rows (direction dir_r at offsets ra_r, rb_r), shared by
// the position and velocity blocks:
//   K_rs = dir_r.dir_s (1/m_a + 1/m_b) + (ra_r x dir_r).I_a^-1 (ra_s x dir_s) + (same for b).
BlockMatrix effective_mass_block(const InverseMass& a, const InverseMass& b, const RowVectors& dir,
                                 const RowVectors& ra, const RowVectors& rb, int rows) {
  RowVectors ua, ub, Iua, Iub;
  for (int r = 0; r < rows; ++r) {
    ua[r] = ra[r].cross(dir[r]);
    ub[r] = rb[r].cross(dir[r]);
    Iua[r] = a.angular * ua[r];
    Iub[r] = b.angular * ub[r];
  }
  const Real linear = a.linear + b.linear;
  BlockMatrix K{};
  for (int r = 0; r < rows; ++r)
    for (int q = r; q < rows; ++q)
      K[r][q] = K[q][r] = dir[r].dot(dir[q]) * linear + ua[r].dot(Iua[q]) + ub[r].dot(Iub[q]);
  return K;
}

// How much a sweep moved the rows: max_r |(K (x - start))_r|, the change of each row's value
// (depth or slip, m; or velocity, m/s) that the sweep's impulses cause. It ignores the directions
// in which a singular block's impulses can drift without moving the bodies (four corners of a face
// share three independent normal directions), where Gauss-Seidel converges slowly but nothing
// physical changes.
Real largest_row_change(const BlockMatrix& K, const std::array<Real, 3 * kMaxPoints>& start,
                        const std::array<Real, 3 * kMaxPoints>& x, int rows) {
  std::array<Real, 3 * kMaxPoints> dx{};
  for (int r = 0; r < rows; ++r) dx[r] = x[r] - start[r];
  Real largest = 0;
  for (int r = 0; r < rows; ++r) {
    Real change = 0;
    for (int q = 0; q < rows; ++q) change += K[r][q] * dx[q];
    largest = std::max(largest, std::abs(change));
  }
  return largest;
}

// The net impulse of a manifold's rows on one body: sum p_r and sum r_r x p_r.
struct NetImpulse {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
  void add(const Vec3& p, const Vec3& r) {
    linear += p;
    angular += r.cross(p);
  }
};

Pose body_pose(const RigidBodyState& s, Index b) { return {s.position[b], s.orientation[b]}; }
Pose start_pose(const RigidBodyState& s, Index b) { return {s.start_position[b], s.start_orientation[b]}; }

// World bounds of body b grown by its margin; planes are unbounded.
void body_bounds(const RigidBodyModel& m, const RigidBodyState& s, Index b, Real margin, Vec3& lo, Vec3& hi) {
  const RigidShape& shape = m.body_shape[b];
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

// Carries stuck slip over from last step's point of the same pair with the same body-frame cores
// (within 5 % of the smaller body's size: the same corner or face point, not a neighbour). A pair
// with a mesh has a manifold per triangle; all of the pair's previous manifolds are searched.
void carry_stuck_slip(const RigidBodyModel& m, RigidContacts& contacts) {
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
      if (before.sliding) continue;
      for (Index i = mf.first; i < mf.first + mf.count; ++i) {
        RigidContactPoint& c = contacts.points[i];
        for (Index j = before.first; j < before.first + before.count; ++j) {
          const RigidContactPoint& p = bp.previous_points[j];
          if ((p.geometry.core_a - c.geometry.core_a).norm() + (p.geometry.core_b - c.geometry.core_b).norm() <
              tolerance) {
            c.stuck_slip = p.stuck_slip;
            break;
          }
        }
      }
    }
  }
}

}  // namespace

void accumulate_stuck_slip(State& state) {
  const RigidBodyState& s = state.rigid;
  RigidContacts& contacts = state.rigid_contacts;
  for (RigidManifold& mf : contacts.manifolds) {
    const Pose pa = body_pose(s, mf.body_a), pb = body_pose(s, mf.body_b);
    const Pose sa = start_pose(s, mf.body_a), sb = start_pose(s, mf.body_b);
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

namespace {

bool joined(const RigidBodyModel& m, Index a, Index b) {
  const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
  return std::binary_search(m.pairs_without_contact.begin(), m.pairs_without_contact.end(), key);
}

// One manifold's block: per point a normal row (C = d >= 0) and two tangent rows (C = slip . t =
// 0, static friction), solved together by projected Gauss-Seidel on the linearised system
//   e + K x = 0 (rows at rest),  x_n >= 0 complementary to d + (K x)_n,
//   |x_t| <= mu_s x_n, else x_t = 0 (the point slides: the velocity pass applies dynamic friction)
// with K_rs = dir_r.dir_s (1/m_a + 1/m_b) + (r_a x dir_r).I_a^-1 (r_a x dir_s) + (same for b),
// then applied as position impulses.
void solve_manifold_block(RigidManifold& mf, RigidContactPoint* points, const BodyHandle& ha, const BodyHandle& hb,
                          const RigidBodyState& s) {
  const Index a = mf.body_a, b = mf.body_b;
  const Pose pa = body_pose(s, a), pb = body_pose(s, b);
  const Pose sa = start_pose(s, a), sb = start_pose(s, b);
  // Only penetrating points enter the block (Mueller 2020 handles a contact when d < 0); slot j
  // holds point active[j] in rows 3j (normal), 3j + 1 and 3j + 2 (tangents).
  std::array<int, kMaxPoints> active{};
  int k = 0;
  std::array<Real, 3 * kMaxPoints> e{}, x{};
  RowVectors dir, ra, rb;  // per row; the three rows of a point share its offsets
  for (int i = 0; i < mf.count; ++i) {
    RigidContactPoint& c = points[i];
    const Vec3 n = contact_normal(mf.frame, c.geometry, pa, pb);
    const Vec3 p_a = pa.to_world(c.geometry.core_a) - c.geometry.radius_a * n;
    const Vec3 p_b = pb.to_world(c.geometry.core_b) + c.geometry.radius_b * n;
    c.normal = n;
    c.offset_a = p_a - pa.position;
    c.offset_b = p_b - pb.position;
    const Real depth = (p_a - p_b).dot(n);
    if (depth >= 0) continue;
    c.material_a = pa.orientation.conjugate() * c.offset_a;
    c.material_b = pb.orientation.conjugate() * c.offset_b;
    // Slip of the two material points (body-frame points) over the substep, plus what the point
    // has slipped since it began to stick.
    const Vec3 slip = (p_a - sa.to_world(c.material_a)) - (p_b - sb.to_world(c.material_b)) + c.stuck_slip;
    const Vec3 t1 = (std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
    const Vec3 t2 = n.cross(t1);
    const int r0 = 3 * k;
    dir[r0] = n;
    dir[r0 + 1] = t1;
    dir[r0 + 2] = t2;
    e[r0] = depth;
    e[r0 + 1] = slip.dot(t1);
    e[r0 + 2] = slip.dot(t2);
    for (int r = r0; r < r0 + 3; ++r) {
      ra[r] = c.offset_a;
      rb[r] = c.offset_b;
    }
    active[k++] = i;
  }
  if (k == 0) {
    mf.sliding = false;
    return;
  }
  const int rows = 3 * k;
  const InverseMass ma = inverse_mass(ha), mb = inverse_mass(hb);
  const BlockMatrix K = effective_mass_block(ma, mb, dir, ra, rb, rows);
  auto residual = [&](int r) {
    Real v = e[r];
    for (int q = 0; q < rows; ++q) v += K[r][q] * x[q];
    return v;
  };
  Real scale = 0;  // m: the largest depth or slip of the block
  for (int r = 0; r < rows; ++r) scale = std::max(scale, std::abs(e[r]));
  const Real tolerance = kBlockTolerance * scale + kPositionFloor;
  auto sweeps = [&](bool friction, int max_sweeps) {
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
      const std::array<Real, 3 * kMaxPoints> start = x;
      for (int j = 0; j < k; ++j) {
        const int rn = 3 * j;
        if (K[rn][rn] > 0) x[rn] = std::max(Real(0), x[rn] - residual(rn) / K[rn][rn]);
        if (!friction) continue;
        for (int r = rn + 1; r < rn + 3; ++r)
          if (K[r][r] > 0) x[r] -= residual(r) / K[r][r];
        // Project onto the friction cone |x_t| <= mu_s x_n.
        const Real ft = std::sqrt(x[rn + 1] * x[rn + 1] + x[rn + 2] * x[rn + 2]);
        const Real bound = mf.static_friction * x[rn];
        if (ft > bound) {
          x[rn + 1] *= bound / ft;
          x[rn + 2] *= bound / ft;
        }
      }
      const Real largest_change = largest_row_change(K, start, x, rows);
      if (largest_change <= tolerance) return;
    }
  };
  // A few sweeps decide most blocks: a resting contact's friction lies well inside its cone, a
  // sliding one's on it at every pushing point. A block left between the two (some points on the
  // cone, some inside) is swept to convergence before it is judged, so that the judgement does not
  // depend on the order of the rows (a box on a slope steeper than its friction angle was held
  // for its first step, or not, depending on the slope's direction).
  auto on_cone = [&](int j) {
    const Real ft = std::sqrt(x[3 * j + 1] * x[3 * j + 1] + x[3 * j + 2] * x[3 * j + 2]);
    return ft >= (1 - 1e-9) * mf.static_friction * x[3 * j];
  };
  sweeps(true, kFirstSweeps);
  int pushing = 0, limited = 0;
  for (int j = 0; j < k; ++j)
    if (x[3 * j] > 0) {
      ++pushing;
      limited += on_cone(j) ? 1 : 0;
    }
  if (limited > 0 && limited < pushing) sweeps(true, kMaxBlockSweeps);
  // Static friction holds only inside the cone (Mueller 2020, eq. 27), judged for the manifold as
  // a whole: when every pushing point's friction sits on its cone, the manifold slides, the
  // friction rows are dropped and the velocity pass applies dynamic friction instead. (Single
  // corners on the cone while others hold is a box that sticks.)
  bool sliding = false;
  for (int j = 0; j < k; ++j) {
    if (x[3 * j] <= 0) continue;
    sliding = on_cone(j);
    if (!sliding) break;
  }
  mf.sliding = sliding;
  if (sliding) {
    for (int j = 0; j < k; ++j) x[3 * j + 1] = x[3 * j + 2] = 0;
    sweeps(false, kMaxBlockSweeps);
  }
  for (int j = 0; j < k; ++j) {
    RigidContactPoint& c = points[active[j]];
    if (x[3 * j] <= 0) continue;
    c.lambda_normal += x[3 * j];
    c.touching = true;
  }
  NetImpulse pa_net, pb_net;
  for (int r = 0; r < rows; ++r)
    if (x[r] != 0) {
      pa_net.add(x[r] * dir[r], ra[r]);
      pb_net.add(-x[r] * dir[r], rb[r]);
    }
  // x += p / m, q += 1/2 [I^-1 (r x p), 0] q with the world inverse inertia of the solve.
  if (!ha.is_world()) {
    *ha.position += ma.linear * pa_net.linear;
    if (ha.rotates()) ha.rotate_by(ma.angular * pa_net.angular);
  }
  if (!hb.is_world()) {
    *hb.position += mb.linear * pb_net.linear;
    if (hb.rotates()) hb.rotate_by(mb.angular * pb_net.angular);
  }
}

// Projected Gauss-Seidel on a manifold's velocity block (rows in triples: normal, two tangents):
//   (K x + v0)_n = target_n,  (K x + v0)_t = 0 subject to |x_t| <= bound (a disc per point),
// swept until a sweep changes no row's velocity by more than kBlockTolerance of the block's speed
// plus kVelocityFloor.
void solve_velocity_block(const BlockMatrix& K, const std::array<Real, 3 * kMaxPoints>& v0,
                          const std::array<Real, 3 * kMaxPoints>& target, const std::array<Real, 3 * kMaxPoints>& bound,
                          int rows, Real speed, std::array<Real, 3 * kMaxPoints>& x) {
  const Real tolerance = kBlockTolerance * speed + kVelocityFloor;
  for (int sweep = 0; sweep < kMaxBlockSweeps; ++sweep) {
    const std::array<Real, 3 * kMaxPoints> start = x;
    for (int r = 0; r < rows; r += 3) {
      for (int q = r; q < r + 3; ++q) {
        if (K[q][q] <= 0) continue;
        Real v = v0[q] - (q == r ? target[r] : 0);
        for (int p = 0; p < rows; ++p) v += K[q][p] * x[p];
        x[q] -= v / K[q][q];
      }
      const Real ft = std::sqrt(x[r + 1] * x[r + 1] + x[r + 2] * x[r + 2]);
      if (ft > bound[r]) {
        x[r + 1] *= bound[r] / ft;
        x[r + 2] *= bound[r] / ft;
      }
    }
    const Real largest_change = largest_row_change(K, start, x, rows);
    if (largest_change <= tolerance) return;
  }
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
  bp.pairs.clear();
  for (Index i = 0; i < n; ++i) {
    const Index a = bp.order[i];
    for (Index j = i + 1; j < n; ++j) {
      const Index b = bp.order[j];
      if (bp.lower[b].x() > bp.upper[a].x()) break;
      if (!m.is_dynamic(a) && !m.is_dynamic(b)) continue;
      if ((bp.lower[a].array() > bp.upper[b].array()).any() || (bp.lower[b].array() > bp.upper[a].array()).any())
        continue;
      if (joined(m, a, b)) continue;
      bp.pairs.push_back({std::min(a, b), std::max(a, b)});
    }
  }
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
    const RigidShape &sa = m.body_shape[a], &sb = m.body_shape[b];
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
      contacts.manifolds.push_back(mf);
      for (int c = 0; c < cm.count; ++c) {
        RigidContactPoint point;
        point.geometry = cm.points[c];
        contacts.points.push_back(point);
      }
    }
  carry_stuck_slip(m, contacts);
}

void reset_rigid_contacts(State& state) {
  for (RigidManifold& mf : state.rigid_contacts.manifolds) mf.touching = false;
  for (RigidContactPoint& c : state.rigid_contacts.points) {
    c.lambda_normal = 0;
    c.touching = false;
  }
}

void project_rigid_contacts(const Model& model, State& state) {
  const RigidBodyModel& m = model.rigid;
  RigidBodyState& s = state.rigid;
  RigidContacts& contacts = state.rigid_contacts;
  for (RigidManifold& mf : contacts.manifolds) {
    const BodyHandle ha = rigid_body_handle(m, s, mf.body_a), hb = rigid_body_handle(m, s, mf.body_b);
    RigidContactPoint* points = contacts.points.data() + mf.first;
    solve_manifold_block(mf, points, ha, hb, s);
    for (Index i = 0; i < mf.count; ++i) mf.touching |= points[i].touching;
  }
}

void rigid_contact_velocities(const Model& model, State& state, Real h) {
  const RigidBodyModel& m = model.rigid;
  RigidBodyState& s = state.rigid;
  RigidContacts& contacts = state.rigid_contacts;
  const Real resting_speed = 2 * model.settings.gravity.norm() * h;
  for (RigidManifold& mf : contacts.manifolds) {
    if (!mf.touching) continue;
    const Index a = mf.body_a, b = mf.body_b;
    const BodyVelocityHandle va = rigid_body_velocity_handle(m, s, a), vb = rigid_body_velocity_handle(m, s, b);
    // Rows of the touching points: normal (restitution) and two tangents (dynamic friction).
    std::array<Real, 3 * kMaxPoints> target{}, bound{}, x{};
    RowVectors dir, ra, rb;
    int rows = 0;
    for (Index i = mf.first; i < mf.first + mf.count; ++i) {
      const RigidContactPoint& c = contacts.points[i];
      if (!c.touching) continue;
      const Vec3& n = c.normal;
      const Vec3 v = va.point_velocity(c.offset_a) - vb.point_velocity(c.offset_b);
      const Vec3 before = (s.velocity_before[a] + s.angular_velocity_before[a].cross(c.offset_a)) -
                          (s.velocity_before[b] + s.angular_velocity_before[b].cross(c.offset_b));
      const Real restitution = std::abs(n.dot(v)) <= resting_speed ? 0 : mf.restitution;
      const Vec3 t1 = (std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
      dir[rows] = n;
      dir[rows + 1] = t1;
      dir[rows + 2] = n.cross(t1);
      // The approach speed is the larger of the one before the solve (Mueller 2020) and the one now:
      // in a row of touching balls the inner contacts were at rest before the solve and are
      // approached only once the manifolds before them in this pass have bounced (Newton's cradle).
      target[rows] = std::max(-restitution * std::min(n.dot(before), n.dot(v)), Real(0));
      bound[rows] = mf.dynamic_friction * c.lambda_normal / h;  // friction impulse limit of this point
      for (int r = rows; r < rows + 3; ++r) {
        ra[r] = c.offset_a;
        rb[r] = c.offset_b;
      }
      rows += 3;
    }
    // Effective masses and the projected Gauss-Seidel solve of
    //   v_n -> target (restitution, Mueller 2020 eq. 34), v_t -> 0 with |p_t| <= mu_k lambda_n / h.
    const InverseMass ma = inverse_mass(va), mb = inverse_mass(vb);
    const BlockMatrix K = effective_mass_block(ma, mb, dir, ra, rb, rows);
    std::array<Real, 3 * kMaxPoints> v0{};
    Real speed = 0;
    for (int r = 0; r < rows; ++r) {
      v0[r] = dir[r].dot(va.point_velocity(ra[r]) - vb.point_velocity(rb[r]));
      speed = std::max({speed, std::abs(v0[r]), target[r]});
    }
    solve_velocity_block(K, v0, target, bound, rows, speed, x);
    NetImpulse pa_net, pb_net;
    for (int r = 0; r < rows; ++r)
      if (x[r] != 0) {
        pa_net.add(x[r] * dir[r], ra[r]);
        pb_net.add(-x[r] * dir[r], rb[r]);
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
