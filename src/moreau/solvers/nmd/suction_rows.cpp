#include "moreau/solvers/nmd/suction_rows.hpp"

#include "moreau/constraints/particle_body_contact_rows.hpp"

namespace moreau {

namespace {

// A surface a cup can seal on: a collider at the step's start, or a rigid body as it stands.
struct Surface {
  const Model& model;
  const State& state;
  Real time;
  Index collider = -1, body = -1;

  ColliderDistance distance(const Vec3& x) const {
    if (collider >= 0) {
      const Collider& c = model.colliders[collider];
      return collider_distance(c, c.position_at(time), x);
    }
    const ParticleBodyNormal near = nearest_on_body(model, state, body, x);
    return {near.surface.distance, near.normal};
  }
  // Whether every rim vertex is within its contact gap plus the seal gap.
  bool holds(const SuctionCup& cup) const {
    for (Index p : cup.rim)
      if (distance(state.position[p]).distance > model.particle_collider_gap[p] + cup.seal_gap) return false;
    return true;
  }
};

// The surface's tangent plane under the rim's centroid: a point on it and its normal.
std::pair<Vec3, Vec3> surface_plane(const SuctionCup& cup, const Surface& surface, const Vec3* x) {
  Vec3 centroid = Vec3::Zero();
  for (Index p : cup.rim) centroid += x[p];
  centroid /= static_cast<Real>(cup.rim.size());
  const ColliderDistance d = surface.distance(centroid);
  return {centroid - d.distance * d.normal, d.normal};
}

// The colliders, then the rigid bodies that are not colliders, until one holds the whole rim.
bool find_seal(const Model& model, const State& state, Real time, const SuctionCup& cup, SuctionCupState& s) {
  for (Index c = 0; c < static_cast<Index>(model.colliders.size()); ++c)
    if (Surface{model, state, time, c, -1}.holds(cup)) {
      s.collider = c;
      return true;
    }
  for (const ObjectInfo& o : model.objects)
    if (o.kind == ObjectKind::rigid_body && Surface{model, state, time, -1, o.body}.holds(cup)) {
      s.body = o.body;
      return true;
    }
  return false;
}

}  // namespace

void add_suction_rows(const Model& model, State& state, const VelocitySpace& space, Real h, Real start_time,
                      NmdBlockInput& in, NmdSystem& system) {
  const Vec3* x = state.position.data();
  for (size_t k = 0; k < model.suction_cups.size(); ++k) {
    const SuctionCup& cup = model.suction_cups[k];
    SuctionCupState& s = state.suction[k];
    if (s.sealed) {
      if (!Surface{model, state, start_time, s.collider, s.body}.holds(cup)) s = SuctionCupState{};  // air rushes in
    } else if (find_seal(model, state, start_time, cup, s)) {
      s.sealed = true;
      s.air_volume = std::numeric_limits<Real>::infinity();  // set from the volume below
    }
    if (!s.sealed) continue;
    const Surface surface{model, state, start_time, s.collider, s.body};
    const auto [point, normal] = surface_plane(cup, surface, x);
    const Vec3 center = s.body >= 0 ? state.rigid.position[s.body] : Vec3::Zero();
    const CavityVolume v = cavity_volume(cup, x, point, normal, center);
    s.volume = v.volume;
    s.area = v.area;
    if (!(v.volume > 0)) {  // the cavity squeezed flat: nothing sealed in
      s = SuctionCupState{};
      continue;
    }
    s.air_volume = std::min(s.air_volume, v.volume);  // the lip lets air out, never in
    const Real p0 = cup.atmospheric_pressure;
    const Real alpha = suction_compliance(p0, s.air_volume, v.volume);

    const int vertices = static_cast<int>(cup.cavity_vertices.size());
    in.resize(1, vertices + (s.body >= 0 ? 1 : 0));
    for (int e = 0; e < vertices; ++e) {
      in.end[e] = space.particle_end(cup.cavity_vertices[e]);
      for (int a = 0; a < 3; ++a) in.at(0, e)[a] = v.gradient[e][a];
    }
    if (s.body >= 0) {  // the body carrying the surface, pulled by the same suction
      in.end[vertices] = space.end(BodyEnd{BodyEndKind::body, s.body});
      const Vec3 linear = -v.area * normal;
      for (int a = 0; a < 3; ++a) {
        in.at(0, vertices)[a] = linear[a];
        in.at(0, vertices)[3 + a] = v.surface_turn[a];
      }
    } else {
      in.known[0] = -v.area * normal.dot(model.colliders[s.collider].velocity);  // the collider's own motion (colliders only translate)
    }
    in.C[0] = alpha * suction_pressure(p0, s.air_volume, v.volume);
    in.compliance(0, 0) = alpha;
    in.upper[0] = 0;  // suction pulls the cavity shut, never pushes it open
    in.kind = NmdBlockKind::bounded;
    in.memory = &s.memory;
    in.memory_rows = 1;
    system.add(in, space, h, model.settings.nmd);
  }
}

void store_suction(const Model& model, State& state, Real h) {
  for (size_t k = 0; k < model.suction_cups.size(); ++k) {
    SuctionCupState& s = state.suction[k];
    s.pressure_difference = s.sealed ? -s.memory / (h * h) : 0;
  }
}

}  // namespace moreau
