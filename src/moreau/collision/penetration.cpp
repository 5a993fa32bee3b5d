#include "moreau/collision/penetration.hpp"

#include <algorithm>

#include "moreau/collision/collider.hpp"
#include "moreau/constraints/contact_rows.hpp"
#include "moreau/constraints/particle_body_contact_rows.hpp"
#include "moreau/constraints/particle_contact_rows.hpp"
#include "moreau/model/model.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

namespace {

// Depth of the rigid contact points of the manifolds that involve `object`.
Real rigid_depth(const Model& model, const State& state, Index object) {
  const RigidContacts& contacts = state.rigid_contacts;
  const RigidBodyState& s = state.rigid;
  Real deepest = 0;
  for (const RigidManifold& mf : contacts.manifolds) {
    const Index a = mf.body_a, b = mf.body_b;
    if (object >= 0 && model.rigid.body_object[a] != object && model.rigid.body_object[b] != object) continue;
    const Pose pa{s.position[a], s.orientation[a]}, pb{s.position[b], s.orientation[b]};
    for (Index i = mf.first; i < mf.first + mf.count; ++i)
      deepest = std::max(deepest, -contact_point_at_poses(mf.frame, contacts.points[i].geometry, pa, pb).separation);
  }
  return deepest;
}

Real particle_body_depth(const Model& model, const State& state, Index object) {
  const ParticleBodyContacts& c = state.particle_body_contacts;
  Real deepest = 0;
  for (size_t q = 0; q < c.size(); ++q) {
    const auto [b, p] = c.pair[q];
    if (object >= 0 && model.rigid.body_object[b] != object && model.particle_object[p] != object) continue;
    const ParticleBodyNormal near = nearest_on_body(model, state, b, state.position[p]);
    deepest = std::max(deepest, model.particle_collider_gap[p] - near.surface.distance);
  }
  return deepest;
}

Real collider_depth(const Model& model, const State& state, Index object) {
  const ColliderContacts& c = state.collider_contacts;
  Real deepest = 0;
  for (size_t q = 0; q < c.size(); ++q) {
    const Index p = c.particle[q];
    const Collider& collider = model.colliders[c.collider[q]];
    if (object >= 0 && model.particle_object[p] != object) continue;
    const ColliderDistance d = collider_distance(collider, collider.position_at(state.time), state.position[p]);
    deepest = std::max(deepest, model.particle_collider_gap[p] - d.distance);
  }
  return deepest;
}

Real particle_pair_depth(const Model& model, const State& state, Index object) {
  const ParticleContacts& c = state.particle_contacts;
  Real deepest = 0;
  for (const auto& [i, j] : c.pair) {
    if (object >= 0 && model.particle_object[i] != object && model.particle_object[j] != object) continue;
    const Real C = pair_contact_normal(state.position[i], state.position[j],
                                       model.particle_radius[i] + model.particle_radius[j]).C;
    deepest = std::max(deepest, -C);
  }
  return deepest;
}

}  // namespace

Real deepest_penetration(const Model& model, const State& state, Index object) {
  return std::max({rigid_depth(model, state, object), particle_body_depth(model, state, object),
                   collider_depth(model, state, object), particle_pair_depth(model, state, object)});
}

}  // namespace moreau
