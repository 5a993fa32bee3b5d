#include "moreau/collision/particle_body_contacts.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/constraints/particle_body_contact_rows.hpp"
#include "moreau/model/state.hpp"
#include "moreau/collision/narrow_phase.hpp"
#include "moreau/collision/point_query.hpp"

namespace moreau {

namespace {

bool takes_part(const Model& model, Index body) {
  return model.objects[model.rigid.body_object[body]].has_bodies();
}

}  // namespace

void detect_particle_body_contacts(const Model& model, State& state) {
  ParticleBodyContacts& c = state.particle_body_contacts;
  c.pair.clear();
  const RigidBodyModel& m = model.rigid;
  const RigidBodyState& s = state.rigid;
  const Index particles = model.particle_count();
  if (particles == 0 || m.empty()) return;
  const Real dt = model.settings.dt, k = model.settings.contact_margin_factor;
  const Real fall = dt * model.settings.gravity.norm();

  // Particles sorted by x (ties by index), with the largest gap and speed for the bounds.
  c.by_x.resize(particles);
  Real max_gap = 0, max_speed = 0;
  for (Index p = 0; p < particles; ++p) {
    c.by_x[p] = p;
    max_gap = std::max(max_gap, model.particle_collider_gap[p]);
    max_speed = std::max(max_speed, state.velocity[p].norm());
  }
  std::sort(c.by_x.begin(), c.by_x.end(), [&](Index a, Index b) {
    const Real xa = state.position[a].x(), xb = state.position[b].x();
    return xa < xb || (xa == xb && a < b);
  });

  for (Index b = 0; b < m.count(); ++b) {
    if (!takes_part(model, b)) continue;
    const Shape& shape = m.body_shape[b];
    const Real body_reach = k * dt * (s.velocity[b].norm() + s.angular_velocity[b].norm() * shape.bounding_radius());
    // World bounds: |R| times the body-frame half extents.
    const Mat3 R = s.orientation[b].toRotationMatrix();
    const Vec3 half = R.cwiseAbs() * shape.local_half_extents() +
                      Vec3::Constant(max_gap + body_reach + k * dt * (max_speed + fall));
    const Vec3 lo = s.position[b] - half, hi = s.position[b] + half;
    auto first = std::lower_bound(c.by_x.begin(), c.by_x.end(), lo.x(),
                                  [&](Index p, Real x) { return state.position[p].x() < x; });
    for (auto it = first; it != c.by_x.end() && state.position[*it].x() <= hi.x(); ++it) {
      const Index p = *it;
      const Vec3& x = state.position[p];
      if (x.y() < lo.y() || x.y() > hi.y() || x.z() < lo.z() || x.z() > hi.z()) continue;
      if (model.particle_inv_mass[p] <= 0 && m.body_inv_mass[b] <= 0) continue;
      if (!state.live(p)) continue;  // a grain its emitter has not released
      if (state.sleep.asleep(p) && !body_wakes_grains(model, state, b)) continue;  // resting on a fixed body
      // A particle joined to the body (a cloth vertex holding a rod's end) does not push it away.
      if (std::binary_search(m.particle_pairs_without_contact.begin(), m.particle_pairs_without_contact.end(),
                             std::array<Index, 2>{b, p}))
        continue;
      const Real reach = model.particle_collider_gap[p] + body_reach +
                         k * dt * ((state.velocity[p] - s.velocity[b]).norm() + fall);
      if (nearest_on_body(model, state, b, x).surface.distance <= reach) c.pair.push_back({b, p});
    }
  }
  std::sort(c.pair.begin(), c.pair.end());
  const size_t n = c.pair.size();
  c.lambda_normal.assign(n, 0);
  c.normal.assign(n, Vec3::UnitY());
  c.offset.assign(n, Vec3::Zero());
  c.static_friction.resize(n);
  c.dynamic_friction.resize(n);
  c.restitution.resize(n);
  c.adhesion.resize(n);
  c.spring.resize(n);
  for (size_t q = 0; q < n; ++q) {
    const auto [b, p] = c.pair[q];
    // Coefficients: the mean of the two sides (Mueller 2020), as for the other contacts.
    const ObjectInfo& particle_object = model.objects[model.particle_object[p]];
    c.static_friction[q] = 0.5 * (particle_object.static_friction + m.body_static_friction[b]);
    c.dynamic_friction[q] = 0.5 * (particle_object.dynamic_friction + m.body_dynamic_friction[b]);
    c.restitution[q] = 0.5 * (particle_object.restitution + m.body_restitution[b]);
    c.adhesion[q] = std::max(particle_object.adhesion, m.body_adhesion[b]);
    c.spring[q] = particle_object.contact_spring;  // a grain's; bodies have none
  }
}

Index touching_particle_body_count(const Model& model, const State& state, Index object) {
  const ParticleBodyContacts& c = state.particle_body_contacts;
  Index count = 0;
  for (size_t q = 0; q < c.size(); ++q) {
    if (c.lambda_normal[q] == 0) continue;  // pushing, or pulling by adhesion
    const auto [b, p] = c.pair[q];
    if (object >= 0 && model.rigid.body_object[b] != object && model.particle_object[p] != object) continue;
    ++count;
  }
  return count;
}

}  // namespace moreau
