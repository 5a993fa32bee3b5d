#include "moreau/solvers/nmd/nmd_assembly.hpp"

#include <omp.h>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/contact_rows.hpp"
#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/neo_hookean_green_strain.hpp"
#include "moreau/constraints/particle_body_contact_rows.hpp"
#include "moreau/constraints/particle_contact_rows.hpp"
#include "moreau/constraints/turning_contact.hpp"
#include "moreau/solvers/nmd/shape_match_rows.hpp"
#include "moreau/solvers/nmd/turning_contact_rows.hpp"

namespace moreau {

namespace {

struct Assembly {
  const Model& model;
  State& state;
  const VelocitySpace& space;
  Real h;
  NmdSystem& system;
  NmdRowMemory& memory;
  NmdBlockInput input;

  void add() { system.add(input, space, h, model.settings.nmd); }
};

// Sizes the input for a row block over particles (a family's RowBlock or a particle contact):
// one end per particle, its R x 3 gradient as the end's linear columns, and C.
template <class Rows>
void set_particle_rows(NmdBlockInput& in, const Rows& rows, const VelocitySpace& space) {
  in.resize(Rows::kRows, Rows::kParticles);
  for (int i = 0; i < Rows::kParticles; ++i) {
    in.end[i] = space.particle_end(rows.particle[i]);
    for (int r = 0; r < Rows::kRows; ++r)
      for (int c = 0; c < 3; ++c) in.at(r, i)[c] = rows.gradient[i](r, c);
  }
  in.C = rows.C;
}

// Sizes the input for a block of body rows (a joint's or a particle-body contact's): two ends,
// their R x 6 Jacobians, C, the diagonal compliance and the force bounds.
void set_body_rows(NmdBlockInput& in, const BodyRows& rows, const VelocitySpace& space) {
  const int R = rows.size();
  in.resize(R, 2);
  for (int e = 0; e < 2; ++e) {
    in.end[e] = space.end(rows.end[e]);
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < 6; ++c) in.at(r, e)[c] = rows.jacobian[e](r, c);
  }
  for (int r = 0; r < R; ++r) {
    in.C[r] = rows.C[r];
    in.compliance(r, r) = rows.compliance[r];
    in.lower[r] = rows.lower[r];
    in.upper[r] = rows.upper[r];
  }
  in.damping_time = rows.damping_time;  // SPOOK's tau: the force -(C + tau dC/dt) / eps
}

bool has_bounds(const NmdBlockInput& in) {
  return (in.lower.array() > -std::numeric_limits<Real>::infinity()).any() ||
         (in.upper.array() < std::numeric_limits<Real>::infinity()).any();
}

// One constraint's rows over its particles, bilateral unless bounded, warm-started from `memory`.
template <class Rows>
void add_rows(Assembly& a, const Rows& rows, Real* memory) {
  NmdBlockInput& in = a.input;
  set_particle_rows(in, rows, a.space);
  in.compliance = rows.compliance;
  in.damping_time = rows.damping_time;
  in.lower = rows.lower;
  in.upper = rows.upper;
  in.kind = has_bounds(in) ? NmdBlockKind::bounded : NmdBlockKind::equality;
  in.memory = memory;
  in.memory_rows = Rows::kRows;
  a.add();
}

// A family's constraints; a Neo-Hookean tetrahedron as its Green-strain rows.
template <class Family>
void add_family(Assembly& a, const Family& family, std::vector<typename Family::Multiplier>& lambda) {
  const Vec3* x = a.state.position.data();
  const Index count = static_cast<Index>(family.size());
  if constexpr (std::is_same_v<Family, NeoHookeanTetConstraints>) {
    a.memory.neo_hookean.resize(count, Eigen::Matrix<Real, 6, 1>::Zero());
    for (Index k = 0; k < count; ++k)
      add_rows(a, neo_hookean_green_strain_rows(family, k, x), a.memory.neo_hookean[k].data());
  } else {
    for (Index k = 0; k < count; ++k) add_rows(a, family.rows(k, x), multiplier_rows<Family>(lambda[k]).data());
  }
}

// The joints' blocks as each joint hands them on.
class JointBlocks final : public BodyRowSink {
 public:
  explicit JointBlocks(Assembly& a) : a_(a) {}
  void set_memory(JointMultipliers& lambda) { memory_ = &lambda; }
  void take(const BodyRows& rows) override {
    NmdBlockInput& in = a_.input;
    set_body_rows(in, rows, a_.space);
    if (rows.velocity_drive) {
      in.level[0] = RowLevel::velocity;
      in.target[0] = rows.target_velocity;
    }
    in.kind = has_bounds(in) ? NmdBlockKind::bounded : NmdBlockKind::equality;
    in.memory = memory_->data() + rows.slot;
    in.memory_rows = rows.size();
    a_.add();
  }

 private:
  Assembly& a_;
  JointMultipliers* memory_ = nullptr;
};

// A joint's `damping` and `angular_damping` as damper blocks (nmd_system.hpp): the anchors'
// relative velocity and the ends' relative angular velocity decay at those rates against the
// ends' effective mass and inertia. No memory: a damper's impulse follows the velocities.
void add_joint_dampers(Assembly& a, const Joint& j) {
  if (j.damping <= 0 && j.angular_damping <= 0) return;
  const JointEndPose pa = end_pose(a.state, j.ends[0]), pb = end_pose(a.state, j.ends[1]);
  const bool rotates = j.ends[0].kind == BodyEndKind::body || j.ends[1].kind == BodyEndKind::body;
  for (const bool angular : {false, true}) {
    const Real rate = angular ? j.angular_damping : j.damping;
    if (rate <= 0 || (angular && !rotates)) continue;
    set_body_rows(a.input, damper_rows(j, pa, pb, angular), a.space);
    for (int r = 0; r < 3; ++r) a.input.level[r] = RowLevel::velocity;
    a.input.damper_rate = rate;
    a.add();
  }
}

// Adhesion (Gascon, Zurdo, Otaduy 2010, "Constraint-based simulation of adhesive contact"): a
// contact point may pull as well as push, down to -A (N). The glue is the contact's own spring of
// compliance eps: it holds while the gap is at most eps A, its stretch at full strength, and lets
// go once pulled further (then the point is an ordinary speculative contact).
Real adhesive_bound(Real adhesion, Real gap, Real compliance) {
  return adhesion > 0 && gap <= compliance * adhesion ? adhesion : 0;
}

// The compliance of a contact's normal row: a grain's spring, else the settings' (hard contacts).
Real contact_compliance(const NmdSettings& settings, const ContactSpring& spring) {
  return spring.soft() ? spring.compliance : settings.contact_compliance;
}

// Makes the sized input a contact block (row 0 normal, rows 1 and 2 friction) with the pair's
// coefficients; `memory` holds the normal impulse, or all three rows' impulses. A soft contact
// (a grain's spring, compliant_contact.hpp) is a row of its own compliance and relaxation time
// that bounces by itself (no restitution); a hard one takes settings.contact_compliance.
void set_contact(NmdBlockInput& in, const NmdSettings& settings, Real static_friction, Real dynamic_friction,
                 Real restitution, Real* memory, int memory_rows, Real adhesion, const ContactSpring& spring = {}) {
  in.kind = NmdBlockKind::contact;
  in.level[1] = in.level[2] = RowLevel::friction;
  in.C[1] = in.C[2] = 0;  // friction rows act on velocities only
  in.lower.setConstant(-std::numeric_limits<Real>::infinity());
  in.upper.setConstant(std::numeric_limits<Real>::infinity());
  in.lower[0] = -adhesion;
  in.compliance.setZero();
  in.compliance(0, 0) = contact_compliance(settings, spring);
  in.damping_time = spring.relaxation_time();
  in.static_friction = static_friction;
  in.dynamic_friction = dynamic_friction;
  in.restitution = spring.soft() ? 0 : restitution;
  in.memory = memory;
  in.memory_rows = memory_rows;
}

void add_collider_contacts(Assembly& a, Real end_time) {
  ColliderContacts& c = a.state.collider_contacts;
  const Vec3* x = a.state.position.data();
  for (size_t q = 0; q < c.size(); ++q) {
    const Index p = c.particle[q];
    const Collider& col = a.model.colliders[c.collider[q]];
    const ColliderDistance d = collider_distance(col, col.position_at(end_time - a.h), x[p]);
    const ParticleContactRows<1> rows = collider_contact_rows(p, d.distance, d.normal, a.model.particle_collider_gap[p],
                                                              c.static_friction[q], Vec3::Zero(), x, x);
    set_particle_rows(a.input, rows, a.space);
    for (int r = 0; r < 3; ++r) a.input.known[r] = -rows.gradient[0].row(r).dot(col.velocity);  // dC/dt = grad . (v_p - v_c)
    set_contact(a.input, a.model.settings.nmd, c.static_friction[q], c.dynamic_friction[q], c.restitution[q],
                &c.lambda_normal[q], 1,
                adhesive_bound(c.adhesion[q], a.input.C[0], contact_compliance(a.model.settings.nmd, c.spring[q])),
                c.spring[q]);
    const Real r = a.model.particle_radius[p];
    add_turning_rows(a.input, a.space, {TurningSide{a.space.turns(p) ? p : -1, r}, TurningSide{}}, d.normal,
                     rows.gradient[0].row(1), rows.gradient[0].row(2), c.rolling_resistance[q] * r);
    a.add();
  }
}

// The pairs in colour order (a greedy colouring of the pairs by the particles they move): the
// sweep schedule (sweep_schedule.hpp) puts a pair one level above the last earlier pair that
// shares a particle, so pairs listed tile by tile, neighbours after neighbours, would make as many
// levels as a tile has pairs, where a colour order makes about as many as there are colours.
void add_particle_contacts(Assembly& a) {
  ParticleContacts& c = a.state.particle_contacts;
  const Vec3* x = a.state.position.data();
  std::vector<std::array<Index, 4>> stencils(c.size());
  for (size_t q = 0; q < c.size(); ++q) stencils[q] = {c.pair[q][0], c.pair[q][1], -1, -1};
  ColorBatches colors;
  const std::vector<Index> order = color_constraints(stencils, a.model.particle_inv_mass, colors);
  for (const Index q : order) {
    const auto [i, j] = c.pair[q];
    const Real ri = a.model.particle_radius[i], rj = a.model.particle_radius[j];
    const ParticleContactRows<2> rows = pair_contact_rows(i, j, ri + rj, c.static_friction[q], x, x);
    if (rows.gradient[0].isZero()) continue;  // coincident centres: no direction
    NmdBlockInput& in = a.input;
    const bool grain_pair = a.space.turns(i) && a.space.turns(j);
    if (grain_pair) {  // the rows in closed form (GrainPairRows)
      in.resize(6, 4, false);
      in.end = {a.space.particle_end(i), a.space.particle_end(j), a.space.spin_end(i), a.space.spin_end(j)};
      in.C[0] = rows.C[0];
    } else {
      set_particle_rows(in, rows, a.space);
    }
    // Cohesion: within its reach a bond pulls with at most F (N), and adds F to the normal force
    // that bounds the friction.
    const Real cohesion = rows.C[0] < c.cohesion_distance[q] ? c.cohesion[q] : 0;
    set_contact(in, a.model.settings.nmd, c.static_friction[q], c.dynamic_friction[q], c.restitution[q],
                &c.lambda_normal[q], 1, cohesion, c.spring[q]);
    in.cohesion = cohesion;
    // Grains touch at the point that splits the centre distance by their radii.
    const Real share = (ri + rj + rows.C[0]) / (ri + rj);
    const Real rolling = c.rolling_resistance[q] * effective_radius(ri, rj);
    const Vec3 n = rows.gradient[0].row(0), t1 = rows.gradient[0].row(1), t2 = rows.gradient[0].row(2);
    if (grain_pair) {
      make_grain_pair(in, n, t1, t2, share * ri, share * rj, rolling);
    } else {
      add_turning_rows(in, a.space,
                       {TurningSide{a.space.turns(i) ? i : -1, share * ri}, TurningSide{a.space.turns(j) ? j : -1, share * rj}},
                       n, t1, t2, rolling);
    }
    a.add();
  }
}

// Every point of every manifold, in manifold order: room for all of them is made at once (each
// point is a block of 3 rows over two bodies, 36 Jacobian entries), then the manifolds are filled
// in parallel, each into its own slots, so the system is the same for any thread count.
void add_rigid_contacts(Assembly& a, int threads) {
  RigidContacts& contacts = a.state.rigid_contacts;
  const Index manifolds = static_cast<Index>(contacts.manifolds.size());
  std::vector<Index> first(manifolds + 1, 0);  // each manifold's first point among all
  for (Index m = 0; m < manifolds; ++m) first[m + 1] = first[m] + contacts.manifolds[m].count;
  const Index points = first[manifolds];
  constexpr Index kRows = 3, kEntries = 3 * 12;
  const NmdSlot base{static_cast<Index>(a.system.blocks.size()), a.system.row_count(),
                     static_cast<Index>(a.system.block_ends.size()), static_cast<Index>(a.system.jacobian.size()), -1};
  a.system.grow(points, 2 * points, kRows * points, kEntries * points, 0);
  const SubstepStart now{a.state.position.data(), a.state.rigid.position.data(), a.state.rigid.orientation.data()};
  constexpr Index kPointsPerThread = 256;  // below this, one thread
#pragma omp parallel num_threads(points >= kPointsPerThread * threads ? threads : 1)
  {
    NmdBlockInput in;
#pragma omp for schedule(static)
    for (Index m = 0; m < manifolds; ++m) {
      RigidManifold& mf = contacts.manifolds[m];
      RigidContactPoint* point = contacts.points.data() + mf.first;
      const ContactRows rows = manifold_rows(mf, point, a.state.rigid, now, ContactPoints::all);
      for (int j = 0; j < rows.points; ++j) {
        in.resize(3, 2);
        for (int e = 0; e < 2; ++e) in.end[e] = a.space.end(rows.end[e]);
        for (int r = 0; r < 3; ++r) {  // point rows (body_rows.hpp) along each direction
          const int row = 3 * j + r;
          const Vec3& d = rows.direction[row];
          const Vec3 angular_a = rows.offset_a[row].cross(d), angular_b = rows.offset_b[row].cross(d);
          for (int c = 0; c < 3; ++c) {
            in.at(r, 0)[c] = d[c];
            in.at(r, 0)[3 + c] = angular_a[c];
            in.at(r, 1)[c] = -d[c];
            in.at(r, 1)[3 + c] = -angular_b[c];
          }
        }
        in.C[0] = rows.C[3 * j];
        set_contact(in, a.model.settings.nmd, mf.static_friction, mf.dynamic_friction, mf.restitution,
                    point[rows.point[j]].row_impulse.data(), 3,
                    adhesive_bound(mf.adhesion, in.C[0], a.model.settings.nmd.contact_compliance));
        const Index k = first[m] + j;  // ContactPoints::all: every point of the manifold, in order
        a.system.fill({base.block + k, base.first_row + kRows * k, base.first_end + 2 * k,
                       base.first_entry + kEntries * k, -1},
                      in, a.space, a.h, a.model.settings.nmd);
      }
    }
  }
}

void add_particle_body_contacts(Assembly& a) {
  ParticleBodyContacts& c = a.state.particle_body_contacts;
  const SubstepStart now{a.state.position.data(), a.state.rigid.position.data(), a.state.rigid.orientation.data()};
  for (size_t q = 0; q < c.size(); ++q) {
    const auto [b, p] = c.pair[q];
    const ParticleBodyContactRows contact =
        particle_body_rows(a.model, a.state, now, b, p, c.static_friction[q], ContactPoints::all);
    set_body_rows(a.input, contact.rows, a.space);
    set_contact(a.input, a.model.settings.nmd, c.static_friction[q], c.dynamic_friction[q], c.restitution[q],
                &c.lambda_normal[q], 1,
                adhesive_bound(c.adhesion[q], a.input.C[0], contact_compliance(a.model.settings.nmd, c.spring[q])),
                c.spring[q]);
    if (a.space.turns(p)) {  // a grain turns against the body, both sides' turning resisted
      // The grain's lever is its distance d from the body's surface point, along -n, where the
      // body's rows act: the pair's impulses then act at one point and exert no net torque, also
      // in a speculative row that closes a gap within the step (d > r) and when pressed in (d < r).
      const Real r = a.model.particle_radius[p];
      const Real arm = std::max(contact.rows.C[0] + a.model.particle_collider_gap[p], Real(0));  // C = d - r
      const Real rolling = a.model.objects[a.model.particle_object[p]].rolling_resistance * r;
      const auto direction = [&](int row) { return Vec3(contact.rows.jacobian[0].row(row).head<3>()); };
      const int body_end = contact.rows.end[0].kind == BodyEndKind::body ? 0 : 1;  // (particle, body) today
      add_turning_rows(a.input, a.space, {TurningSide{p, arm}, TurningSide{-1, 0, body_end}}, direction(0),
                       direction(1), direction(2), rolling);
    }
    a.add();
  }
}

}  // namespace

void assemble_nmd_system(const Model& model, State& state, const VelocitySpace& space, Real h, Real end_time,
                         NmdSystem& system, NmdRowMemory& memory, int threads) {
  system.clear();
  Assembly a{model, state, space, h, system, memory, {}};
  for_each_family(model.constraints, state.constraint_lambda,
                  [&](const auto& family, auto& lambda, int) { add_family(a, family, lambda); });
  if (!model.shape_matching.empty()) add_shape_match_rows(model, state, space, h, a.input, system, memory.shape_match);
  JointBlocks joints(a);
  for (size_t k = 0; k < model.joints.size(); ++k) {
    joints.set_memory(state.joint_lambda[k]);
    joint_rows({state, model.joints[k], h, joint_coordinate(model.joints[k], state), JointRowSet::all}, joints);
    add_joint_dampers(a, model.joints[k]);
  }
  add_collider_contacts(a, end_time);
  add_particle_contacts(a);
  add_rigid_contacts(a, threads);
  add_particle_body_contacts(a);
}

}  // namespace moreau
