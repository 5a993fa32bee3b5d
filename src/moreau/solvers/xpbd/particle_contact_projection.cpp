#include "moreau/solvers/xpbd/particle_contact_projection.hpp"

#include <cmath>

#include "moreau/constraints/particle_contact_rows.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

void project_collider_contacts(const Model& model, State& state, const SubstepContext& s, Real substep_end_time) {
  ColliderContacts& c = state.collider_contacts;
  const Index groups = static_cast<Index>(c.group_offsets.size()) - 1;
#pragma omp for schedule(static)
  for (Index g = 0; g < groups; ++g) {
    for (Index q = c.group_offsets[g]; q < c.group_offsets[g + 1]; ++q) {
      const Index p = c.particle[q];
      const Collider& col = model.colliders[c.collider[q]];
      const Real w = s.inv_mass[p];
      const ColliderDistance d = collider_distance(col, col.position_at(substep_end_time), s.x[p]);
      c.normal[q] = d.normal;
      const Real C = d.distance - model.particle_collider_gap[p];  // the normal row
      if (C >= 0) continue;
      const Real dl = -C / w;
      c.lambda_normal[q] += dl;
      s.x[p] += w * dl * d.normal;
      // Static friction: cancel the slip relative to the collider while it is inside the cone.
      const Vec3 slip = tangential_part((s.x[p] - s.x_start[p]) - s.h * col.velocity, d.normal);
      if (slip.norm() < c.static_friction[q] * c.lambda_normal[q] * w) s.x[p] -= slip;
    }
  }
}

void project_particle_contacts(const Model& model, State& state, const SubstepContext& s) {
  ParticleContacts& c = state.particle_contacts;
  for_each_by_color(c.batches, [&](Index q) {
    const auto [i, j] = c.pair[q];
    const Real wi = s.inv_mass[i], wj = s.inv_mass[j], w = wi + wj;
    const auto [C, n] = pair_contact_normal(s.x[i], s.x[j], model.particle_radius[i] + model.particle_radius[j]);
    if (n.isZero()) return;  // coincident centres: no direction to push along
    c.normal[q] = n;
    // Apart beyond the bond's reach (0 without cohesion): no contact.
    if (C >= c.cohesion_distance[q]) return;
    // Cohesion: within its reach the bond pulls the pair together, with a force of at most F
    // (the substep's multiplier, a force times h^2, bounded below by -F h^2), and adds F h^2 to
    // the normal multiplier that bounds the friction.
    const Real bond = c.cohesion[q] * s.h * s.h;
    const Real dl = std::max(-C / w, -bond - c.lambda_normal[q]);
    c.lambda_normal[q] += dl;
    s.x[i] += wi * dl * n;
    s.x[j] -= wj * dl * n;
    const Vec3 slip = tangential_part((s.x[i] - s.x_start[i]) - (s.x[j] - s.x_start[j]), n);
    if (slip.norm() < c.static_friction[q] * (c.lambda_normal[q] + bond) * w) {
      s.x[i] -= (wi / w) * slip;
      s.x[j] += (wj / w) * slip;
    }
  });
}

Vec3 friction_velocity_change(const Vec3& v_rel, const Vec3& n, Real lambda_n, Real w, Real mu_k, Real h) {
  const Vec3 vt = v_rel - n.dot(v_rel) * n;
  const Real vt_norm = vt.norm();
  if (!(vt_norm > 0)) return Vec3::Zero();
  return -vt / vt_norm * std::min(mu_k * w * lambda_n / h, vt_norm);
}

Vec3 contact_velocity_change(const Vec3& v_rel, const Vec3& v_rel_before, const Vec3& n, Real lambda_n, Real w,
                             Real mu_k, Real e, Real h, Real g) {
  const Real vn = n.dot(v_rel);
  Vec3 dv = friction_velocity_change(v_rel, n, lambda_n, w, mu_k, h);
  const Real vn_before = n.dot(v_rel_before);
  if (std::abs(vn) <= 2 * g * h) e = 0;
  dv += n * (-vn + std::max(-e * vn_before, 0.0));
  return dv;
}

void collider_contact_velocities(const Model& model, State& state, const Vec3* velocity_before, Real h) {
  ColliderContacts& c = state.collider_contacts;
  const Real g = model.settings.gravity.norm();
  const Index groups = static_cast<Index>(c.group_offsets.size()) - 1;
#pragma omp for schedule(static)
  for (Index gi = 0; gi < groups; ++gi) {
    for (Index q = c.group_offsets[gi]; q < c.group_offsets[gi + 1]; ++q) {
      if (c.lambda_normal[q] <= 0) continue;
      const Index p = c.particle[q];
      const Vec3& vc = model.colliders[c.collider[q]].velocity;
      const Vec3 dv = contact_velocity_change(state.velocity[p] - vc, velocity_before[p] - vc, c.normal[q],
                                              c.lambda_normal[q], model.particle_inv_mass[p], c.dynamic_friction[q],
                                              c.restitution[q], h, g);
      state.velocity[p] += dv;
    }
  }
}

void particle_contact_velocities(const Model& model, State& state, const Vec3* velocity_before, Real h) {
  ParticleContacts& c = state.particle_contacts;
  const Real g = model.settings.gravity.norm();
  for_each_by_color(c.batches, [&](Index q) {
    const auto [i, j] = c.pair[q];
    // A bond within its reach adds F h^2 to the normal multiplier of the friction; a pair that
    // only pulled gets no restitution (its separation is the bond's to stop).
    Real bond = 0;
    if (c.cohesion[q] > 0) {
      const Real gap = (state.position[i] - state.position[j]).norm() - model.particle_radius[i] - model.particle_radius[j];
      if (gap < c.cohesion_distance[q]) bond = c.cohesion[q] * h * h;
    }
    if (c.lambda_normal[q] + bond <= 0) return;
    const Real wi = model.particle_inv_mass[i], wj = model.particle_inv_mass[j], w = wi + wj;
    const Vec3 v_rel = state.velocity[i] - state.velocity[j];
    const Vec3 dv = c.lambda_normal[q] > 0
                        ? contact_velocity_change(v_rel, velocity_before[i] - velocity_before[j], c.normal[q],
                                                  c.lambda_normal[q] + bond, w, c.dynamic_friction[q],
                                                  c.restitution[q], h, g)
                        : friction_velocity_change(v_rel, c.normal[q], bond + c.lambda_normal[q], w,
                                                   c.dynamic_friction[q], h);
    // Impulse p = dv / (wi + wj): particle i gains wi p, particle j loses wj p.
    state.velocity[i] += (wi / w) * dv;
    state.velocity[j] -= (wj / w) * dv;
  });
}

}  // namespace moreau
