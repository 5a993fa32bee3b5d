#include "moreau/solvers/xpbd/particle_contact_projection.hpp"

#include <array>
#include <cmath>

#include "moreau/constraints/particle_contact_rows.hpp"
#include "moreau/constraints/turning_contact.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

namespace {

// A collider as a contact's side j: it neither moves in the solve nor turns.
constexpr ContactSide kColliderSide{0, 0, 0};

// The sides of a pair at centre distance d: the contact point splits d in proportion to the
// radii, so the two arms add up to d and an impulse pair at the contact point leaves the
// angular momentum unchanged.
std::array<ContactSide, 2> pair_sides(Real wi, Real wj, Real inv_inertia_i, Real inv_inertia_j, Real ri, Real rj, Real d) {
  const Real share = d / (ri + rj);
  return {ContactSide{wi, inv_inertia_i, share * ri}, ContactSide{wj, inv_inertia_j, share * rj}};
}

// The bounds of a contact's friction impulses at the position level: mu N with N its normal
// multiplier (kg m), and mu_r R* N for the rolling resistance (kg m^2).
struct FrictionBounds {
  Real static_friction, kinetic_friction, rolling;
};

// Friction (and rolling resistance) at the position level (turning_contact.hpp).
// Sides that do not turn (cloth, soft bodies; Mueller et al. 2020): all or nothing, the slip is
// cancelled while that takes less than mu_s N, else the velocity pass applies dynamic friction.
// A grain: Coulomb friction at the position level (as in Macklin et al. 2014, sec. 6.1), with the
// turn. The substep's friction impulse P and rolling impulse L accumulate over the iterations
// (`total_p`, `total_L`) and it is they that the bounds hold, as in projected Gauss-Seidel: the
// increments that cancel the current slip and turn are added; an L beyond mu_r R* N is cut back
// to it (the sides turn against that much), the slip then cancelled given it; a P beyond mu_s N
// slides, cut back to mu_k N, the turn then cancelled within its bound. Returns the increments.
// The position level holds all of a grain's friction (the velocity pass adds none).
StickImpulses friction_impulses(const TurningContact& t, const Vec3& n, const Vec3& slip, const Vec3& roll,
                                const FrictionBounds& bound, Vec3& total_p, Vec3& total_L) {
  auto clamp = [](const Vec3& v, Real most) {
    const Real length = v.norm();
    return length > most ? Vec3(v * (most / length)) : v;
  };
  if (t.k <= 0) {
    const Vec3 p = -slip / t.w_t;
    if (p.norm() < bound.static_friction) return {p, Vec3::Zero()};
    return {Vec3::Zero(), Vec3::Zero()};
  }
  StickImpulses d = stick_impulses(t, n, slip, roll);
  if ((total_L + d.L).norm() > bound.rolling) {
    d.L = clamp(total_L + d.L, bound.rolling) - total_L;
    d.p = (-slip - t.c * n.cross(d.L)) / t.w_t;
  }
  const Vec3 P = total_p + d.p;
  const Real P_norm = P.norm();
  if (P_norm >= bound.static_friction && P_norm > 0) {
    d.p = P * std::min(1.0, bound.kinetic_friction / P_norm) - total_p;  // never past sticking (mu_k > mu_s)
    d.L = clamp(total_L + (-roll + t.c * n.cross(d.p)) / t.k, bound.rolling) - total_L;
  }
  total_p += d.p;
  total_L += d.L;
  return d;
}

// The velocity pass of one contact between sides of inverse masses w_i and w_j (j a collider
// when v_j is null; its velocity is in v_rel): restitution along n when the contact `bounces`
// (a hard contact that pushed; a spring's bounce is its own); dynamic friction (Mueller et al.
// 2020) unless a side is a grain (`turns`), whose friction is all at the position level.
void contact_velocity_pass(Real wi, Real wj, bool turns, const Vec3& n, Vec3& v_i, Vec3* v_j, const Vec3& v_rel,
                           const Vec3& v_rel_before, Real normal_multiplier, bool bounces, Real mu_k, Real e, Real h,
                           Real g) {
  const Real w = wi + wj;
  if (w <= 0) return;  // neither side can move (a particle held in an emitter's nozzle)
  const Vec3 dv = turns     ? (bounces ? restitution_velocity_change(v_rel, v_rel_before, n, e, h, g) : Vec3::Zero())
                  : bounces ? contact_velocity_change(v_rel, v_rel_before, n, normal_multiplier, w, mu_k, e, h, g)
                           : friction_velocity_change(v_rel, n, normal_multiplier, w, mu_k, h);
  // Impulse dv / w: side i gains w_i of it per unit, side j loses w_j.
  v_i += (wi / w) * dv;
  if (v_j) *v_j -= (wj / w) * dv;
}

}  // namespace

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
      const Vec3& n = d.normal;
      c.normal[q] = n;
      if (w <= 0) continue;  // held in an emitter's nozzle: it keeps its course
      const Real C = d.distance - model.particle_collider_gap[p];  // the normal row
      const ContactSpring& spring = c.spring[q];
      // A hard contact acts while it overlaps; a spring also while its push lasts, to let go of it.
      if (C >= 0 && (!spring.soft() || c.lambda_normal[q] <= 0)) continue;
      const Real dl = spring.soft() ? compliant_normal_increment(spring, C, n.dot((s.x[p] - s.x_start[p]) - s.h * col.velocity),
                                                                 c.lambda_normal[q], w, 0, s.h)
                                    : -C / w;
      c.lambda_normal[q] += dl;
      s.x[p] += w * dl * n;
      // Static friction and rolling resistance against the collider, which moves by h v_c.
      const ContactSide side{w, s.inv_inertia[p], model.particle_radius[p]};
      const Vec3 slip = tangential_part((s.x[p] - s.x_start[p]) - s.h * col.velocity, n) - side.arm * s.turn[p].cross(n);
      const Vec3& roll = s.turn[p];
      const Real normal = c.lambda_normal[q];
      const StickImpulses stick = friction_impulses(
          turning_contact(side, kColliderSide), n, slip, roll,
          {c.static_friction[q] * normal, c.dynamic_friction[q] * normal, c.rolling_resistance[q] * side.arm * normal},
          c.lambda_friction[q], c.lambda_rolling[q]);
      s.x[p] += w * stick.p;
      if (side.inv_inertia > 0) s.turn[p] += turn_change(side, n, stick.p, stick.L);
    }
  }
}

void project_particle_contacts(const Model& model, State& state, const SubstepContext& s) {
  ParticleContacts& c = state.particle_contacts;
  for_each_by_tile(c.batches, [&](Index q) {
    const auto [i, j] = c.pair[q];
    const Real wi = s.inv_mass[i], wj = s.inv_mass[j], w = wi + wj;
    const Real ri = model.particle_radius[i], rj = model.particle_radius[j];
    const auto [C, n] = pair_contact_normal(s.x[i], s.x[j], ri + rj);
    if (n.isZero()) return;  // coincident centres: no direction to push along
    c.normal[q] = n;
    if (w <= 0) return;  // neither side can move (a particle held in an emitter's nozzle, one pinned)
    // Apart beyond the bond's reach (0 without cohesion): no contact, unless a spring's push is
    // to be let go of.
    const ContactSpring& spring = c.spring[q];
    if (C >= c.cohesion_distance[q] && (!spring.soft() || c.lambda_normal[q] <= 0)) return;
    // Cohesion: within its reach the bond pulls the pair together, with a force of at most F
    // (the substep's multiplier, a force times h^2, bounded below by -F h^2), and adds F h^2 to
    // the normal multiplier that bounds the friction.
    const Real bond = c.cohesion[q] * s.h * s.h;
    const Real dl =
        spring.soft()
            ? compliant_normal_increment(spring, C, n.dot((s.x[i] - s.x_start[i]) - (s.x[j] - s.x_start[j])),
                                         c.lambda_normal[q], w, -bond, s.h)
            : std::max(-C / w, -bond - c.lambda_normal[q]);
    c.lambda_normal[q] += dl;
    s.x[i] += wi * dl * n;
    s.x[j] -= wj * dl * n;
    // Static friction and rolling resistance at the contact point (turning_contact.hpp).
    // The arms split the centre distance ri + rj + C found by this projection (that after the
    // normal push, ri + rj + C + w dl, conserves the angular momentum of the test of
    // test_grain_rolling.cpp less well: 2.2 % against 1.8 %).
    const auto [side_i, side_j] = pair_sides(wi, wj, s.inv_inertia[i], s.inv_inertia[j], ri, rj, ri + rj + C);
    const Vec3 slip = tangential_part((s.x[i] - s.x_start[i]) - (s.x[j] - s.x_start[j]), n) -
                      (side_i.arm * s.turn[i] + side_j.arm * s.turn[j]).cross(n);
    const Vec3 roll = s.turn[i] - s.turn[j];
    const Real normal = c.lambda_normal[q] + bond;
    const StickImpulses stick =
        friction_impulses(turning_contact(side_i, side_j), n, slip, roll,
                          {c.static_friction[q] * normal, c.dynamic_friction[q] * normal,
                           c.rolling_resistance[q] * effective_radius(ri, rj) * normal},
                          c.lambda_friction[q], c.lambda_rolling[q]);
    s.x[i] += wi * stick.p;
    s.x[j] -= wj * stick.p;
    if (side_i.inv_inertia > 0) s.turn[i] += turn_change(side_i, n, stick.p, stick.L);
    if (side_j.inv_inertia > 0) s.turn[j] += turn_change(side_j, -n, -stick.p, -stick.L);
  });
}

Vec3 friction_velocity_change(const Vec3& v_rel, const Vec3& n, Real lambda_n, Real w, Real mu_k, Real h) {
  const Vec3 vt = v_rel - n.dot(v_rel) * n;
  const Real vt_norm = vt.norm();
  if (!(vt_norm > 0)) return Vec3::Zero();
  return -vt / vt_norm * std::min(mu_k * w * lambda_n / h, vt_norm);
}

Vec3 restitution_velocity_change(const Vec3& v_rel, const Vec3& v_rel_before, const Vec3& n, Real e, Real h, Real g) {
  const Real vn = n.dot(v_rel);
  const Real vn_before = n.dot(v_rel_before);
  if (std::abs(vn) <= 2 * g * h) e = 0;
  return n * (-vn + std::max(-e * vn_before, 0.0));
}

Vec3 contact_velocity_change(const Vec3& v_rel, const Vec3& v_rel_before, const Vec3& n, Real lambda_n, Real w,
                             Real mu_k, Real e, Real h, Real g) {
  return friction_velocity_change(v_rel, n, lambda_n, w, mu_k, h) +
         restitution_velocity_change(v_rel, v_rel_before, n, e, h, g);
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
      contact_velocity_pass(moving_inverse_mass(model, state, p), 0, model.particle_inv_inertia[p] > 0, c.normal[q],
                            state.velocity[p], nullptr, state.velocity[p] - vc, velocity_before[p] - vc,
                            c.lambda_normal[q], !c.spring[q].soft(), c.dynamic_friction[q], c.restitution[q], h, g);
    }
  }
}

void particle_contact_velocities(const Model& model, State& state, const Vec3* velocity_before, Real h) {
  ParticleContacts& c = state.particle_contacts;
  const Real g = model.settings.gravity.norm();
  for_each_by_tile(c.batches, [&](Index q) {
    const auto [i, j] = c.pair[q];
    const Real ri = model.particle_radius[i], rj = model.particle_radius[j];
    // A bond within its reach adds F h^2 to the normal multiplier of the friction; a pair that
    // only pulled gets no restitution (its separation is the bond's to stop).
    Real bond = 0;
    if (c.cohesion[q] > 0) {
      const Real gap = (state.position[i] - state.position[j]).norm() - ri - rj;
      if (gap < c.cohesion_distance[q]) bond = c.cohesion[q] * h * h;
    }
    if (c.lambda_normal[q] + bond <= 0) return;
    const bool turns = model.particle_inv_inertia[i] > 0 || model.particle_inv_inertia[j] > 0;
    contact_velocity_pass(moving_inverse_mass(model, state, i), moving_inverse_mass(model, state, j), turns, c.normal[q],
                          state.velocity[i], &state.velocity[j],
                          state.velocity[i] - state.velocity[j], velocity_before[i] - velocity_before[j],
                          c.lambda_normal[q] + bond, c.lambda_normal[q] > 0 && !c.spring[q].soft(), c.dynamic_friction[q],
                          c.restitution[q], h, g);
  });
}

}  // namespace moreau
