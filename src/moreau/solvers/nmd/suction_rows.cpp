#include "moreau/solvers/nmd/suction_rows.hpp"

namespace moreau {

namespace {

// Whether every rim vertex is within its contact gap plus the seal gap of collider c.
bool rim_touches(const Model& model, const SuctionCup& cup, const Collider& c, const Vec3& center, const Vec3* x) {
  for (Index p : cup.rim)
    if (collider_distance(c, center, x[p]).distance > model.particle_collider_gap[p] + cup.seal_gap) return false;
  return true;
}

// The collider's tangent plane under the rim's centroid: a point on it and its normal.
std::pair<Vec3, Vec3> surface_plane(const SuctionCup& cup, const Collider& c, const Vec3& center, const Vec3* x) {
  Vec3 centroid = Vec3::Zero();
  for (Index p : cup.rim) centroid += x[p];
  centroid /= static_cast<Real>(cup.rim.size());
  const ColliderDistance d = collider_distance(c, center, centroid);
  return {centroid - d.distance * d.normal, d.normal};
}

}  // namespace

void add_suction_rows(const Model& model, State& state, const VelocitySpace& space, Real h, Real start_time,
                      NmdBlockInput& in, NmdSystem& system) {
  const Vec3* x = state.position.data();
  for (size_t k = 0; k < model.suction_cups.size(); ++k) {
    const SuctionCup& cup = model.suction_cups[k];
    SuctionCupState& s = state.suction[k];
    if (s.sealed) {
      const Collider& c = model.colliders[s.collider];
      if (!rim_touches(model, cup, c, c.position_at(start_time), x)) s = SuctionCupState{};  // air rushes in
    } else {
      for (size_t c = 0; c < model.colliders.size() && !s.sealed; ++c) {
        const Collider& col = model.colliders[c];
        if (!rim_touches(model, cup, col, col.position_at(start_time), x)) continue;
        s.sealed = true;
        s.collider = static_cast<Index>(c);
        s.air_volume = std::numeric_limits<Real>::infinity();  // set from the volume below
      }
    }
    if (!s.sealed) continue;
    const Collider& c = model.colliders[s.collider];
    const auto [point, normal] = surface_plane(cup, c, c.position_at(start_time), x);
    const CavityVolume v = cavity_volume(cup, x, point, normal);
    s.volume = v.volume;
    s.area = v.area;
    if (!(v.volume > 0)) {  // the cavity squeezed flat: nothing sealed in
      s = SuctionCupState{};
      continue;
    }
    s.air_volume = std::min(s.air_volume, v.volume);  // the lip lets air out, never in
    const Real p0 = cup.atmospheric_pressure;
    const Real alpha = suction_compliance(p0, s.air_volume, v.volume);

    in.resize(1, static_cast<int>(cup.cavity_vertices.size()));
    for (size_t e = 0; e < cup.cavity_vertices.size(); ++e) {
      in.end[e] = space.particle_end(cup.cavity_vertices[e]);
      for (int a = 0; a < 3; ++a) in.at(0, static_cast<int>(e))[a] = v.gradient[e][a];
    }
    in.C[0] = alpha * suction_pressure(p0, s.air_volume, v.volume);
    in.known[0] = -v.area * normal.dot(c.velocity);  // the surface's own motion (colliders only translate)
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
