#include "moreau/fluids/solid_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "moreau/fluids/boundary_sampling.hpp"
#include "moreau/model/model.hpp"
#include "moreau/collision/shape_surface.hpp"

namespace moreau {

namespace {

// Barycentric coordinates (u, v, w) of the centroids of the n^2 sub-triangles of a triangle
// split n times along each edge: "upward" ones at ((i + 1/3) / n, (j + 1/3) / n), "downward" ones
// at ((i + 2/3) / n, (j + 2/3) / n).
std::vector<Vec3> sub_triangle_centroids(int n) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      const Real u = (i + 1.0 / 3) / n, v = (j + 1.0 / 3) / n;
      out.emplace_back(1 - u - v, u, v);
      if (i + j + 1 < n) {
        const Real a = (i + 2.0 / 3) / n, b = (j + 2.0 / 3) / n;
        out.emplace_back(1 - a - b, a, b);
      }
    }
  return out;
}

// Barycentric coordinates of q in the tetrahedron (a, b, c, d).
std::array<Real, 4> tet_barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& q) {
  Mat3 edges;
  edges << b - a, c - a, d - a;
  const Vec3 l = edges.partialPivLu().solve(q - a);
  return {1 - l.sum(), l.x(), l.y(), l.z()};
}

using Face = std::array<Index, 3>;

Face sorted_face(Index a, Index b, Index c) {
  Face f{a, b, c};
  std::sort(f.begin(), f.end());
  return f;
}

struct Sampler {
  const Model& model;
  Real r;
  FluidSolidSamples out;
  std::vector<Vec3> rest;  // rest positions of the current object's samples

  void add(Index object, const std::array<Index, 4>& particle, const std::array<Real, 4>& weight) {
    Vec3 x = Vec3::Zero();
    for (int k = 0; k < 4; ++k) x += weight[k] * model.particle_rest_position[particle[k]];
    out.particle.push_back(particle);
    out.weight.push_back(weight);
    out.object.push_back(object);
    out.body.push_back(-1);
    out.body_point.push_back(Vec3::Zero());
    out.body_weight.push_back(0);
    out.friction.push_back(model.objects[object].fluid_friction);
    rest.push_back(x);
  }

  int subdivisions(const Vec3& a, const Vec3& b, const Vec3& c) const {
    const Real area = 0.5 * (b - a).cross(c - a).norm();
    return std::max(1, static_cast<int>(std::ceil(std::sqrt(2 * area) / (2 * r))));
  }

  void sample_cloth(Index object, const ObjectInfo& info) {
    const auto& X = model.particle_rest_position;
    for (const Face& t : info.surface) {
      for (const Vec3& b : sub_triangle_centroids(subdivisions(X[t[0]], X[t[1]], X[t[2]])))
        add(object, {t[0], t[1], t[2], t[0]}, {b[0], b[1], b[2], 0.0});
    }
  }

  void sample_soft_body(Index object, const ObjectInfo& info) {
    const auto& X = model.particle_rest_position;
    std::map<Face, Index> face_tet;                    // each face -> a tetrahedron that has it
    std::map<Index, std::vector<Index>> vertex_tets;  // vertex -> tetrahedra around it
    for (Index t = 0; t < static_cast<Index>(info.tets.size()); ++t) {
      const auto& v = info.tets[t];
      for (int skip = 0; skip < 4; ++skip) {
        Face f{};
        for (int k = 0, m = 0; k < 4; ++k)
          if (k != skip) f[m++] = v[k];
        face_tet[sorted_face(f[0], f[1], f[2])] = t;
      }
      for (Index p : v) vertex_tets[p].push_back(t);
    }
    for (const Face& f : info.surface) {
      const auto& owner = info.tets[face_tet.at(sorted_face(f[0], f[1], f[2]))];
      Index apex = owner[0];
      for (Index p : owner)
        if (p != f[0] && p != f[1] && p != f[2]) apex = p;
      Vec3 inward = (X[f[1]] - X[f[0]]).cross(X[f[2]] - X[f[0]]).normalized();
      if (inward.dot(X[apex] - X[f[0]]) < 0) inward = -inward;
      // Candidate tetrahedra: those around the face's vertices (a point r inside is in one of
      // them unless the body is thinner than r there; then the nearest is clamped onto it).
      std::vector<Index> candidates;
      for (Index p : f) candidates.insert(candidates.end(), vertex_tets[p].begin(), vertex_tets[p].end());
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      for (const Vec3& b : sub_triangle_centroids(subdivisions(X[f[0]], X[f[1]], X[f[2]]))) {
        const Vec3 q = b[0] * X[f[0]] + b[1] * X[f[1]] + b[2] * X[f[2]] + r * inward;
        std::array<Real, 4> best{};
        Index best_tet = -1;
        Real best_min = -1e300;
        for (Index t : candidates) {
          const auto& v = info.tets[t];
          const auto l = tet_barycentric(X[v[0]], X[v[1]], X[v[2]], X[v[3]], q);
          const Real lowest = *std::min_element(l.begin(), l.end());
          if (lowest > best_min) best_min = lowest, best = l, best_tet = t;
        }
        if (best_min < 0) {  // outside every candidate: clamp onto the nearest one
          Real sum = 0;
          for (Real& l : best) sum += (l = std::max(l, 0.0));
          for (Real& l : best) l /= sum;
        }
        add(object, info.tets[best_tet], best);
      }
    }
  }

  // A rigid body: its surface triangles (body frame) sampled like a soft body's, each sample r
  // inside along the face normal. The body's generalised inverse mass at a point r from its centre,
  // for a push in any direction, is at most 1/m + |r|^2 max(I^-1): the split of
  // split_solid_masses uses that bound.
  void sample_rigid_body(Index object, Index b) {
    const RigidBodyModel& m = model.rigid;
    const TriangleMesh surface = shape_surface(m.body_shape[b]);
    const auto& X = surface.vertices;
    const Real max_inv_inertia = m.body_inv_inertia[b].maxCoeff();
    for (const auto& t : surface.triangles) {
      const Vec3 inward = -(X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]).normalized();
      for (const Vec3& w : sub_triangle_centroids(subdivisions(X[t[0]], X[t[1]], X[t[2]]))) {
        const Vec3 q = w[0] * X[t[0]] + w[1] * X[t[1]] + w[2] * X[t[2]] + r * inward;
        out.particle.push_back({0, 0, 0, 0});
        out.weight.push_back({0, 0, 0, 0});
        out.object.push_back(object);
        out.body.push_back(b);
        out.body_point.push_back(q);
        out.body_weight.push_back(m.body_inv_mass[b] + q.squaredNorm() * max_inv_inertia);
        out.friction.push_back(model.objects[object].fluid_friction);
        rest.push_back(q);  // the body frame is as good as any for the volumes
      }
    }
  }

  // A continuum: one sample per particle at its centre (weight 1) carrying the particle's rest
  // volume. A uniformly filled region's Akinci volume 1 / sum W is its cells' volume, so the body
  // counts in the fluid's density as the fluid filling its place would: water meets it at rest
  // density and a floating body displaces its own volume. Its surface lies half a spacing beyond
  // the outer samples (one fluid radius when the spacings match).
  // The particles an emitter pours are not samples: they would stand at its opening until
  // released (model/particle_emitter.hpp).
  void sample_continuum(Index object, const ObjectInfo& info) {
    for (Index p = info.particle_begin; p < model.initial_particle_end(object); ++p) {
      add(object, {p, p, p, p}, {1, 0, 0, 0});
      out.volume.push_back(model.continuum.rest_volume[model.continuum.index_of(p)]);
    }
    rest.clear();
  }

  void finish_object(Real spacing, const CubicSplineKernel& kernel) {
    const std::vector<Real> volume = akinci_volumes(rest, spacing, kernel);
    out.volume.insert(out.volume.end(), volume.begin(), volume.end());
    rest.clear();
  }
};

}  // namespace

FluidSolidSamples sample_fluid_solids(const Model& model, Real particle_radius, const CubicSplineKernel& kernel) {
  Sampler sampler{model, particle_radius, {}, {}};
  for (Index o = 0; o < static_cast<Index>(model.objects.size()); ++o) {
    const ObjectInfo& info = model.objects[o];
    if (!info.fluid_coupling) continue;
    if (info.kind == ObjectKind::continuum) {
      sampler.sample_continuum(o, info);
      continue;
    }
    if (info.kind == ObjectKind::cloth) sampler.sample_cloth(o, info);
    else if (info.kind == ObjectKind::soft_body) sampler.sample_soft_body(o, info);
    else continue;
    sampler.finish_object(2 * particle_radius, kernel);
  }
  FluidSolidSamples& s = sampler.out;
  s.body_begin.push_back(s.size());
  for (Index b = 0; b < model.rigid.count(); ++b) {
    const Index o = model.rigid.body_object[b];
    const ObjectInfo& info = model.objects[o];
    if (info.kind != ObjectKind::rigid_body || !info.fluid_coupling) continue;
    sampler.sample_rigid_body(o, b);
    sampler.finish_object(2 * particle_radius, kernel);
    s.sampled_body.push_back(b);
    s.body_begin.push_back(s.size());
  }
  s.any_friction = std::any_of(s.friction.begin(), s.friction.end(), [](Real f) { return f > 0; });
  for (Index k = 0; k < s.size(); ++k) s.any_particle_friction |= s.body[k] < 0 && s.friction[k] > 0;

  // Particle -> (sample, weight), ordered by particle, then sample: each particle gathers its
  // reaction in a fixed order.
  std::vector<std::array<Index, 3>> entries;  // particle, sample, slot
  for (Index k = 0; k < s.size(); ++k)
    for (int slot = 0; slot < 4; ++slot)
      if (s.weight[k][slot] != 0) entries.push_back({s.particle[k][slot], k, slot});
  std::sort(entries.begin(), entries.end());
  s.coupled_begin.push_back(0);
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const auto [p, k, slot] = entries[e];
    if (e > 0 && entries[e - 1][0] != p) s.coupled_begin.push_back(static_cast<Index>(e));
    if (e == 0 || entries[e - 1][0] != p) s.coupled_particle.push_back(p);
    s.coupled_sample.push_back(k);
    s.coupled_weight.push_back(s.weight[k][slot]);
  }
  s.coupled_begin.push_back(static_cast<Index>(entries.size()));
  if (entries.empty()) s.coupled_begin = {0};
  return s;
}

}  // namespace moreau
