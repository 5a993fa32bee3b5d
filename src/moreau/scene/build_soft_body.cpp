#include <fmt/format.h>

#include <algorithm>

#include "moreau/geometry/mesh_generators.hpp"
#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/scene/memory_estimate.hpp"
#include "moreau/scene/object_builders.hpp"

namespace moreau {

namespace {

TetMesh read_soft_body_mesh(const JsonObject& mesh, SceneBuildContext& ctx) {
  const std::string type = mesh.choice("type", {"box", "msh", "tetgen", "obj"});
  TetMesh out;
  std::string source = mesh.path();
  if (type == "box") {
    const Vec3 lo = mesh.vec3("min"), hi = mesh.vec3("max");
    if (!((hi - lo).minCoeff() > 0)) mesh.fail("max", "max must exceed min along every axis");
    const auto cells = mesh.integers("cells", 3, 1);
    const int per_cell = mesh.integer("tets_per_cell", 6, 5, 6);
    check_memory(mesh, "cells", double(cells[0]) * cells[1] * cells[2] * per_cell, memory_cost::tetrahedron, "tetrahedra");
    out = make_box_tets(lo, hi, {cells[0], cells[1], cells[2]}, per_cell == 5 ? CellSplit::five : CellSplit::six);
  } else if (type == "msh") {
    source = resolve_path(ctx, mesh.string("file"));
    out = read_gmsh_msh4(source);
  } else if (type == "tetgen") {
    source = resolve_path(ctx, mesh.string("file"));  // base name: <file>.node and <file>.ele
    out = read_tetgen(source + ".node", source + ".ele");
  } else {
    source = resolve_path(ctx, mesh.string("file"));
    out = tetrahedralize_obj(source, mesh.number("quality", 1.5, Range::closed(1.1, 10)),
                             mesh.number("max_volume", 0.0, Range::non_negative()));
  }
  if (type != "box") {
    const Real scale = mesh.number("scale", 1.0, Range::positive());
    const Vec3 translate = mesh.vec3("translate", Vec3::Zero());
    for (auto& v : out.vertices) v = scale * v + translate;
  }
  mesh.finish();
  orient_and_validate_tets(out, source);
  return out;
}

}  // namespace

void build_soft_body(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  const Index object_index = static_cast<Index>(m.objects.size());
  const TetMesh mesh = read_soft_body_mesh(object.object("mesh"), ctx);

  const JsonObject material = object.object("material");
  material.choice("model", "neo_hookean", {"neo_hookean"});
  const Real youngs = material.number("youngs_modulus", Range::positive());
  const Real poisson = material.number("poisson_ratio", Range::open(-1, 0.5));
  const Real density = material.number("density", Range::positive());
  const Real damping = material.number("damping", 0.0, Range::non_negative());
  const bool has_volume = material.has("volume_compliance");
  const Real volume_compliance = material.number("volume_compliance", 0.0, Range::non_negative());
  material.finish();

  // Lumped masses: a quarter of each tetrahedron's mass to each vertex.
  std::vector<Real> masses(mesh.vertices.size(), 0.0);
  for (const auto& t : mesh.tets) {
    const Real v = tet_signed_volume(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]);
    for (Index k : t) masses[k] += density * v / 4;
  }
  const auto boundary = tet_boundary_faces(mesh);
  const auto boundary_edges = triangle_edges(boundary);
  Real edge_sum = 0;
  for (const auto& e : boundary_edges) edge_sum += (mesh.vertices[e[0]] - mesh.vertices[e[1]]).norm();
  const Real radius = object.number("collision_radius", 0.5 * edge_sum / boundary_edges.size(), Range::positive());

  // Initial velocity: v + omega x (x - center of mass).
  const Vec3 velocity = object.vec3("velocity", Vec3::Zero());
  const Vec3 omega = object.vec3("angular_velocity", Vec3::Zero());
  Vec3 com = Vec3::Zero();
  Real total = 0;
  for (size_t i = 0; i < masses.size(); ++i) {
    com += masses[i] * mesh.vertices[i];
    total += masses[i];
  }
  com /= total;
  // A solid's surface vertices lie on its surface: by default they touch colliders directly.
  const Real gap = object.number("collider_gap", 0.0, Range::non_negative());
  add_particles(ctx, info, mesh.vertices, masses, radius, gap, velocity);
  for (Index p = info.particle_begin; p < info.particle_end; ++p)
    ctx.initial_velocity[p] += omega.cross(m.particle_rest_position[p] - com);

  info.kind = ObjectKind::soft_body;
  info.self_collision = object.boolean("self_collision", false);
  info.fluid_coupling = object.boolean("fluid_coupling", true);
  read_contact_material(object, info.static_friction, info.dynamic_friction, info.restitution);
  read_pins(object, info, ctx);

  const Index base = info.particle_begin;
  for (const auto& f : boundary) info.surface.push_back({base + f[0], base + f[1], base + f[2]});
  for (const auto& t : mesh.tets) {
    const std::array<Index, 4> g{base + t[0], base + t[1], base + t[2], base + t[3]};
    const std::array<Vec3, 4> rest{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]};
    info.tets.push_back(g);
    m.family<NeoHookeanTetConstraints>().add(g, rest, youngs, poisson, damping, object_index);
    if (has_volume) m.family<TetVolumeConstraints>().add(g, rest, volume_compliance, damping, object_index);
  }
  // Only surface vertices can touch anything.
  std::vector<Index> surface_vertices;
  for (const auto& f : boundary) surface_vertices.insert(surface_vertices.end(), f.begin(), f.end());
  std::sort(surface_vertices.begin(), surface_vertices.end());
  surface_vertices.erase(std::unique(surface_vertices.begin(), surface_vertices.end()), surface_vertices.end());
  for (Index v : surface_vertices) m.contact_particle.push_back(base + v);
}

}  // namespace moreau
