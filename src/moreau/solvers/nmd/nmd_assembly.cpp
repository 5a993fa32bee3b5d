#include "moreau/solvers/nmd/nmd_assembly.hpp"

#include "moreau/constraints/contact_rows.hpp"
#include "moreau/constraints/particle_body_contact_rows.hpp"
#include "moreau/constraints/particle_contact_rows.hpp"

namespace moreau {

namespace {

struct Assembly {
  const Model& model;
  State& state;
  const VelocitySpace& space;
  Real h;
  NmdSystem& system;
  NmdBlockInput input;

  void add() { system.add(input, space, h, model.settings.nmd); }
};

// A family's constraint k: its rows over its particles, bilateral unless bounded.
template <class Family>
void add_family(Assembly& a, const Family& family, std::vector<typename Family::Multiplier>& lambda) {
  using Rows = typename Family::Rows;
  for (Index k = 0; k < static_cast<Index>(family.size()); ++k) {
    const Rows rows = family.rows(k, a.state.position.data());
    NmdBlockInput& in = a.input;
    in.resize(Rows::kRows, Rows::kParticles);
    const bool bounded = (rows.lower.array() > -std::numeric_limits<Real>::infinity()).any() ||
                         (rows.upper.array() < std::numeric_limits<Real>::infinity()).any();
    in.kind = bounded ? NmdBlockKind::bounded : NmdBlockKind::equality;
    for (int i = 0; i < Rows::kParticles; ++i) {
      in.end[i] = a.space.particle_end(rows.particle[i]);
      for (int r = 0; r < Rows::kRows; ++r)
        for (int c = 0; c < 3; ++c) in.jacobian(r, 6 * i + c) = rows.gradient[i](r, c);
    }
    in.C = rows.C;
    in.compliance = rows.compliance;
    in.damping_time = rows.damping_time;
    in.lower = rows.lower;
    in.upper = rows.upper;
    in.memory = multiplier_rows<Family>(lambda[k]).data();
    in.memory_rows = Rows::kRows;
    a.add();
  }
}

// The joints' blocks as each joint hands them on.
class JointBlocks final : public BodyRowSink {
 public:
  explicit JointBlocks(Assembly& a) : a_(a) {}
  void set_memory(JointMultipliers& lambda) { memory_ = &lambda; }
  void take(const BodyRows& rows) override {
    NmdBlockInput& in = a_.input;
    const int R = rows.size();
    in.resize(R, 2);
    bool bounded = false;
    for (int e = 0; e < 2; ++e) {
      in.end[e] = a_.space.end(rows.end[e]);
      for (int r = 0; r < R; ++r)
        for (int c = 0; c < 6; ++c) in.jacobian(r, 6 * e + c) = rows.jacobian[e](r, c);
    }
    for (int r = 0; r < R; ++r) {
      in.C[r] = rows.C[r];
      in.compliance(r, r) = rows.compliance[r];
      in.lower[r] = rows.lower[r];
      in.upper[r] = rows.upper[r];
      bounded |= std::isfinite(rows.lower[r]) || std::isfinite(rows.upper[r]);
    }
    if (rows.velocity_drive) {
      in.level[0] = RowLevel::velocity;
      in.target[0] = rows.target_velocity;
    }
    in.kind = bounded ? NmdBlockKind::bounded : NmdBlockKind::equality;
    in.memory = memory_->data() + rows.slot;
    in.memory_rows = R;
    a_.add();
  }

 private:
  Assembly& a_;
  JointMultipliers* memory_ = nullptr;
};

// Fills a contact block's rows: normal, then friction along t1 and t2.
void set_contact_levels(NmdBlockInput& in, Real compliance, Real static_friction, Real dynamic_friction,
                        Real restitution) {
  in.kind = NmdBlockKind::contact;
  in.level[1] = in.level[2] = RowLevel::friction;
  in.lower[0] = 0;
  in.compliance(0, 0) = compliance;
  in.static_friction = static_friction;
  in.dynamic_friction = dynamic_friction;
  in.restitution = restitution;
}

void add_collider_contacts(Assembly& a, Real end_time) {
  ColliderContacts& c = a.state.collider_contacts;
  const Real compliance = a.model.settings.nmd.contact_compliance;
  for (size_t q = 0; q < c.size(); ++q) {
    const Index p = c.particle[q];
    const Collider& col = a.model.colliders[c.collider[q]];
    const ColliderDistance d = collider_distance(col, col.position_at(end_time - a.h), a.state.position[p]);
    c.normal[q] = d.normal;
    const Vec3* x = a.state.position.data();
    const ParticleContactRows<1> rows = collider_contact_rows(p, d.distance, d.normal, a.model.particle_collider_gap[p],
                                                              c.static_friction[q], Vec3::Zero(), x, x);
    NmdBlockInput& in = a.input;
    in.resize(3, 1);
    in.end[0] = a.space.particle_end(p);
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) in.jacobian(r, k) = rows.gradient[0](r, k);
      in.known[r] = -rows.gradient[0].row(r).dot(col.velocity);  // dC/dt = grad . (v_p - v_collider)
    }
    in.C[0] = rows.C[0];
    set_contact_levels(in, compliance, c.static_friction[q], c.dynamic_friction[q], c.restitution[q]);
    in.memory = &c.lambda_normal[q];
    in.memory_rows = 1;
    a.add();
  }
}

void add_particle_contacts(Assembly& a) {
  ParticleContacts& c = a.state.particle_contacts;
  const Real compliance = a.model.settings.nmd.contact_compliance;
  const Vec3* x = a.state.position.data();
  for (size_t q = 0; q < c.size(); ++q) {
    const auto [i, j] = c.pair[q];
    const ParticleContactRows<2> rows = pair_contact_rows(
        i, j, a.model.particle_radius[i] + a.model.particle_radius[j], c.static_friction[q], x, x);
    if (rows.gradient[0].isZero()) continue;  // coincident centres: no direction
    c.normal[q] = rows.gradient[0].row(0).transpose();
    NmdBlockInput& in = a.input;
    in.resize(3, 2);
    for (int e = 0; e < 2; ++e) {
      in.end[e] = a.space.particle_end(rows.particle[e]);
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) in.jacobian(r, 6 * e + k) = rows.gradient[e](r, k);
    }
    in.C[0] = rows.C[0];
    set_contact_levels(in, compliance, c.static_friction[q], c.dynamic_friction[q], c.restitution[q]);
    in.memory = &c.lambda_normal[q];
    in.memory_rows = 1;
    a.add();
  }
}

void add_rigid_contacts(Assembly& a) {
  RigidContacts& contacts = a.state.rigid_contacts;
  const Real compliance = a.model.settings.nmd.contact_compliance;
  const SubstepStart now{a.state.position.data(), a.state.rigid.position.data(), a.state.rigid.orientation.data()};
  for (RigidManifold& mf : contacts.manifolds) {
    RigidContactPoint* points = contacts.points.data() + mf.first;
    const ContactRows rows = manifold_rows(mf, points, a.state.rigid, now, ContactPoints::all);
    for (int j = 0; j < rows.points; ++j) {
      NmdBlockInput& in = a.input;
      in.resize(3, 2);
      for (int e = 0; e < 2; ++e) in.end[e] = a.space.end(rows.end[e]);
      for (int r = 0; r < 3; ++r) {
        const int row = 3 * j + r;
        const Vec3& d = rows.direction[row];
        in.jacobian.row(r).segment<3>(0) = d.transpose();
        in.jacobian.row(r).segment<3>(3) = rows.offset_a[row].cross(d).transpose();
        in.jacobian.row(r).segment<3>(6) = -d.transpose();
        in.jacobian.row(r).segment<3>(9) = -rows.offset_b[row].cross(d).transpose();
      }
      in.C[0] = rows.C[3 * j];
      set_contact_levels(in, compliance, mf.static_friction, mf.dynamic_friction, mf.restitution);
      in.memory = points[rows.point[j]].row_impulse.data();
      in.memory_rows = 3;
      a.add();
    }
  }
}

void add_particle_body_contacts(Assembly& a) {
  ParticleBodyContacts& c = a.state.particle_body_contacts;
  const Real compliance = a.model.settings.nmd.contact_compliance;
  const SubstepStart now{a.state.position.data(), a.state.rigid.position.data(), a.state.rigid.orientation.data()};
  for (size_t q = 0; q < c.size(); ++q) {
    const auto [b, p] = c.pair[q];
    const ParticleBodyContactRows contact =
        particle_body_rows(a.model, a.state, now, b, p, c.static_friction[q], ContactPoints::all);
    const BodyRows& rows = contact.rows;
    c.normal[q] = rows.jacobian[0].row(0).head<3>().transpose();
    c.offset[q] = nearest_on_body(a.model, a.state, b, a.state.position[p]).offset;
    NmdBlockInput& in = a.input;
    in.resize(3, 2);
    for (int e = 0; e < 2; ++e) {
      in.end[e] = a.space.end(rows.end[e]);
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 6; ++k) in.jacobian(r, 6 * e + k) = rows.jacobian[e](r, k);
    }
    in.C[0] = rows.C[0];
    set_contact_levels(in, compliance, c.static_friction[q], c.dynamic_friction[q], c.restitution[q]);
    in.memory = &c.lambda_normal[q];
    in.memory_rows = 1;
    a.add();
  }
}

}  // namespace

void assemble_nmd_system(const Model& model, State& state, const VelocitySpace& space, Real h, Real end_time,
                         NmdSystem& system) {
  system.clear();
  Assembly a{model, state, space, h, system, {}};
  for_each_family(model.constraints, state.constraint_lambda,
                  [&](const auto& family, auto& lambda, int) { add_family(a, family, lambda); });
  JointBlocks joints(a);
  for (size_t k = 0; k < model.joints.size(); ++k) {
    joints.set_memory(state.joint_lambda[k]);
    joint_rows({state, model.joints[k], h, joint_coordinate(model.joints[k], state), JointRowSet::all}, joints);
  }
  add_collider_contacts(a, end_time);
  add_particle_contacts(a);
  add_rigid_contacts(a);
  add_particle_body_contacts(a);
}

}  // namespace moreau
