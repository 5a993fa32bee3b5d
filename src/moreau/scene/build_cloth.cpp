#include <fmt/format.h>

#include <cmath>

#include "moreau/geometry/mesh_generators.hpp"
#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/scene/memory_estimate.hpp"
#include "moreau/scene/object_builders.hpp"

namespace moreau {

namespace {

TriangleMesh read_cloth_mesh(const JsonObject& mesh, SceneBuildContext& ctx) {
  const std::string type = mesh.choice("type", {"grid", "obj"});
  TriangleMesh out;
  if (type == "grid") {
    const Vec2 size = mesh.vec2("size", Range::positive());
    const auto res = mesh.integers("resolution", 2, 2);
    const Vec3 center = mesh.vec3("center", Vec3::Zero());
    check_memory(mesh, "resolution", double(res[0]) * res[1], memory_cost::cloth_cell, "grid cells");
    out = make_grid_sheet(size, {res[0], res[1]}, center);
    // Optional rotation about the sheet's centre (world x, then y, then z): a curtain is
    // "rotation_deg": [90, 0, 0].
    const Mat3 rotation = rotation_from_degrees(mesh.vec3("rotation_deg", Vec3::Zero()));
    for (auto& v : out.vertices) v = center + rotation * (v - center);
  } else {
    out = read_obj_triangles(resolve_path(ctx, mesh.string("file")));
    const Real scale = mesh.number("scale", 1.0, Range::positive());
    const Vec3 translate = mesh.vec3("translate", Vec3::Zero());
    for (auto& v : out.vertices) v = scale * v + translate;
  }
  mesh.finish();
  for (size_t t = 0; t < out.triangles.size(); ++t) {
    const auto& k = out.triangles[t];
    const Real area2 = (out.vertices[k[1]] - out.vertices[k[0]]).cross(out.vertices[k[2]] - out.vertices[k[0]]).norm();
    if (!(area2 > 0)) mesh.fail("type", fmt::format("triangle {} of the cloth mesh is degenerate (zero area)", t));
  }
  return out;
}

}  // namespace

void build_cloth(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  const Index object_index = static_cast<Index>(m.objects.size());
  const TriangleMesh mesh = read_cloth_mesh(object.object("mesh"), ctx);

  const JsonObject material = object.object("material");
  // Mass: an area density (kg/m^2) lumped to the vertices, or one mass per vertex (kg), as
  // position-based libraries often give every particle.
  if (material.has("area_density") == material.has("vertex_mass"))
    material.fail("area_density", "give the cloth's mass as either area_density (kg/m^2) or vertex_mass (kg per vertex)");
  const bool per_vertex = material.has("vertex_mass");
  const Real area_density = per_vertex ? 0 : material.number("area_density", Range::positive());
  const Real vertex_mass = per_vertex ? material.number("vertex_mass", Range::positive()) : 0;
  const Real damping = material.number("damping", 0.0, Range::non_negative());
  const bool membrane = material.has("youngs_modulus");
  Real youngs = 0, poisson = 0, thickness = 0;
  if (membrane) {
    youngs = material.number("youngs_modulus", Range::positive());
    poisson = material.number("poisson_ratio", 0.3, Range::open(-1, 0.5));
    thickness = material.number("thickness", Range::positive());
    if (material.has("stretch_compliance"))
      material.fail("stretch_compliance", "give either a membrane (youngs_modulus, poisson_ratio, thickness) or "
                                          "stretch_compliance, not both");
  }
  const Real stretch_compliance = material.number("stretch_compliance", 0.0, Range::non_negative());
  if (material.has("bending_stiffness") && material.has("bend_compliance"))
    material.fail("bend_compliance", "give either bending_stiffness (N m) or bend_compliance (1/(N m)), not both");
  Real bending_stiffness = membrane ? youngs * thickness * thickness * thickness / (12 * (1 - poisson * poisson)) : 0;
  bending_stiffness = material.number("bending_stiffness", bending_stiffness, Range::non_negative());
  const bool has_bend_compliance = material.has("bend_compliance");
  const Real bend_compliance = material.number("bend_compliance", 0.0, Range::non_negative());
  const bool isometric = material.choice("bending_model", "dihedral", {"dihedral", "isometric"}) == "isometric";
  material.finish();

  // Lumped masses: a third of each triangle's mass to each of its vertices.
  std::vector<Real> masses(mesh.vertices.size(), vertex_mass);
  Real edge_sum = 0;
  const auto edges = triangle_edges(mesh.triangles);
  for (const auto& t : mesh.triangles) {
    const Real area = 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
    if (!per_vertex)
      for (Index v : t) masses[v] += area * area_density / 3;
  }
  for (const auto& e : edges) edge_sum += (mesh.vertices[e[0]] - mesh.vertices[e[1]]).norm();
  const Real mean_edge = edge_sum / edges.size();
  const Real radius = object.number("collision_radius", 0.5 * mean_edge, Range::positive());

  // A sheet has no volume: it keeps `collider_gap` (default: its collision radius) from colliders.
  const Real gap = object.number("collider_gap", radius, Range::non_negative());
  add_particles(ctx, info, mesh.vertices, masses, radius, gap, object.vec3("velocity", Vec3::Zero()));
  info.kind = ObjectKind::cloth;
  info.self_collision = object.boolean("self_collision", true);
  info.fluid_coupling = object.boolean("fluid_coupling", true);
  read_contact_material(object, info.static_friction, info.dynamic_friction, info.restitution);
  read_pins(object, info, ctx);

  const Index base = info.particle_begin;
  auto X = [&](Index v) { return m.particle_rest_position[base + v]; };
  for (const auto& t : mesh.triangles) info.surface.push_back({base + t[0], base + t[1], base + t[2]});

  if (membrane) {
    for (const auto& t : mesh.triangles)
      m.family<TriangleStrainConstraints>().add({base + t[0], base + t[1], base + t[2]}, X(t[0]), X(t[1]), X(t[2]), youngs, poisson, thickness,
                            damping, object_index);
  } else {
    for (const auto& e : edges)
      m.family<DistanceConstraints>().add(base + e[0], base + e[1], (X(e[0]) - X(e[1])).norm(), stretch_compliance, damping, object_index);
  }
  if (has_bend_compliance || bending_stiffness > 0) {
    for (const Hinge& h : triangle_hinges(mesh.triangles)) {
      const Hinge g{base + h.e0, base + h.e1, base + h.o0, base + h.o1};
      const Real theta0 = evaluate_dihedral(X(h.e0), X(h.e1), X(h.o0), X(h.o1)).theta;
      const Real angle_compliance =
          has_bend_compliance
              ? bend_compliance
              : hinge_compliance_from_bending_stiffness(X(h.e0), X(h.e1), X(h.o0), X(h.o1), bending_stiffness);
      if (!isometric) {
        m.family<DihedralBendingConstraints>().add(g, theta0, angle_compliance, damping, object_index);
        continue;
      }
      // The isometric model is exact only for a flat rest shape; 1e-3 rad tolerates mesh-file round-off.
      if (std::abs(theta0) > 1e-3)
        material.fail("bending_model", fmt::format("isometric bending needs a flat rest shape, but the hinge on "
                                                   "vertices {} and {} is bent by {:.3g} degrees at rest; use \"dihedral\"",
                                                   h.e0, h.e1, theta0 * 180 / kPi));
      m.family<IsometricBendingConstraints>().add(g, X(h.e0), X(h.e1), X(h.o0), X(h.o1), angle_compliance, damping, object_index);
    }
  }
  for (Index p = info.particle_begin; p < info.particle_end; ++p) m.contact_particle.push_back(p);
}

}  // namespace moreau
