// "kind": "shape_matched" objects: particles on a cubic lattice of spacing 2 r filling boxes,
// held in their rest shape by shape matching (Mueller et al. 2005) over one cluster of all of
// them or overlapping spherical clusters; the particles touch other objects through the particle
// contacts (with friction and restitution) but not each other.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "moreau/scene/spec_builders.hpp"

namespace moreau {

ShapeMatchedSpec read_shape_matched(const JsonObject& object) {
  ShapeMatchedSpec spec;
  for (const JsonObject& block : object.object_list("blocks")) spec.blocks.push_back(read_block(block));
  spec.radius = object.number("radius");
  spec.density = object.number("density", spec.density);
  spec.frequency = read_optional_number(object, "frequency");
  if (auto clusters = object.optional_object("clusters")) {
    spec.cluster_radius = clusters->number("radius");
    spec.cluster_spacing = read_optional_number(*clusters, "spacing");
    clusters->finish();
  }
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  spec.contact = read_contact_material(object);
  return spec;
}

void add_shape_matched(const ShapeMatchedSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  const Real r = place.number("radius", spec.radius, Range::positive());
  const Real density = place.number("density", spec.density, Range::positive());
  const Real omega = spec.frequency ? 2 * kPi * place.number("frequency", *spec.frequency, Range::positive()) : 0;
  if (spec.blocks.empty()) place.fail("blocks", "a shape-matched object needs at least one block {\"min\", \"max\"} to fill");

  // The lattice: spacing 2 r, each particle carrying the mass of its cube of the block.
  const Real spacing = 2 * r, particle_mass = density * spacing * spacing * spacing;
  std::vector<Vec3> positions;
  constexpr Index kMaxParticles = 10'000'000;
  for (size_t b = 0; b < spec.blocks.size(); ++b) {
    const SpecPlace block = place.at(fmt::format("blocks[{}]", b));
    const Vec3 lo = block.vector("min", spec.blocks[b].min), hi = block.vector("max", spec.blocks[b].max);
    if ((hi.array() - lo.array() < spacing * (1 - 1e-9)).any())
      block.fail("max", fmt::format("the block must be at least one particle diameter ({} m) across in every direction", spacing));
    Eigen::Array3d count = ((hi - lo).array() / spacing + 1e-9).floor();
    if (count.prod() > kMaxParticles)
      block.fail("max", fmt::format("the block holds {:.3g} particles; at most {} per object", count.prod(), kMaxParticles));
    for (int i = 0; i < count.x(); ++i)
      for (int j = 0; j < count.y(); ++j)
        for (int k = 0; k < count.z(); ++k) positions.push_back(lo + Vec3::Constant(r) + spacing * Vec3(i, j, k));
  }
  if (static_cast<Index>(positions.size()) > kMaxParticles)
    place.fail("blocks", fmt::format("the blocks hold {} particles; at most {} per object", positions.size(), kMaxParticles));
  if (positions.size() < 4) place.fail("blocks", "a shape-matched object needs at least 4 particles to have a shape");
  set_contact_material(spec.contact, place, info);
  info.kind = ObjectKind::shape_matched;
  info.self_collision = false;  // the clusters hold the particles apart
  info.fluid_coupling = false;
  add_particles(ctx, info, positions, std::vector<Real>(positions.size(), particle_mass), r, r,
                place.vector("velocity", spec.velocity));
  for (Index p = info.particle_begin; p < info.particle_end; ++p) m.contact_particle.push_back(p);

  // Clusters: one of every particle, or spheres of the cluster radius around the points of a
  // lattice of the cluster spacing over the particles' bounding box (those with at least 4
  // particles not all in one plane).
  const Index object = static_cast<Index>(m.objects.size());
  std::vector<Index> all(positions.size());
  for (Index p = 0; p < static_cast<Index>(all.size()); ++p) all[p] = info.particle_begin + p;
  if (!spec.cluster_radius) {
    m.shape_matching.add(all, m.particle_rest_position, m.particle_mass, omega, object);
    return;
  }
  const Real radius = place.number("clusters.radius", *spec.cluster_radius, Range::positive());
  const Real step = spec.cluster_spacing ? place.number("clusters.spacing", *spec.cluster_spacing, Range::positive()) : radius;
  Vec3 lo = positions[0], hi = positions[0];
  for (const Vec3& x : positions) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const Eigen::Array3i cells = (((hi - lo).array() / step) + 1e-9).floor().cast<int>() + 1;
  if (static_cast<double>(cells.prod()) > 1e6)
    place.fail("clusters.spacing", fmt::format("{} cluster centres; at most a million (space them wider)", cells.prod()));
  std::vector<char> covered(positions.size(), 0);
  std::vector<Index> members;
  for (int i = 0; i < cells.x(); ++i)
    for (int j = 0; j < cells.y(); ++j)
      for (int k = 0; k < cells.z(); ++k) {
        const Vec3 center = lo + step * Vec3(i, j, k);
        members.clear();
        Vec3 mean = Vec3::Zero();
        for (Index p : all)
          if ((m.particle_rest_position[p] - center).norm() <= radius) members.push_back(p), mean += m.particle_rest_position[p];
        if (members.size() < 4) continue;
        mean /= static_cast<Real>(members.size());
        Mat3 spread = Mat3::Zero();
        for (Index p : members) spread += (m.particle_rest_position[p] - mean) * (m.particle_rest_position[p] - mean).transpose();
        if (Eigen::SelfAdjointEigenSolver<Mat3>(spread).eigenvalues()[0] <= 1e-6 * r * r) continue;  // flat: no rotation fit
        m.shape_matching.add(members, m.particle_rest_position, m.particle_mass, omega, object);
        for (Index p : members) covered[p - info.particle_begin] = 1;
      }
  for (size_t p = 0; p < covered.size(); ++p)
    if (!covered[p])
      place.fail("clusters.radius", fmt::format("the particle at ({:.4g}, {:.4g}, {:.4g}) m is in no cluster; widen the "
                                                "clusters (radius {} m) or space them closer",
                                                positions[p].x(), positions[p].y(), positions[p].z(), radius));
}

}  // namespace moreau
