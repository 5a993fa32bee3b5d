// "kind": "soft_body": a tetrahedral mesh of Neo-Hookean or St. Venant-Kirchhoff material.
#include <fmt/format.h>

#include <algorithm>

#include "moreau/geometry/mesh_generators.hpp"
#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/scene/memory_estimate.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

SoftBodySpec read_soft_body(const JsonObject& object) {
  SoftBodySpec spec;
  const JsonObject mesh = object.object("mesh");
  const std::string type = mesh.choice("type", {"box", "msh", "tetgen", "obj"});
  if (type == "box") {
    TetBox box;
    box.min = to_vector3(mesh.vec3("min"));
    box.max = to_vector3(mesh.vec3("max"));
    const auto cells = mesh.integers("cells", 3, 1);
    box.cells = {cells[0], cells[1], cells[2]};
    box.tets_per_cell = mesh.integer("tets_per_cell", box.tets_per_cell, 5, 6);
    spec.mesh = box;
  } else if (type == "obj") {
    TetrahedralizedObj obj;
    obj.file = read_mesh_file(mesh);
    obj.quality = mesh.number("quality", obj.quality);
    obj.max_volume = mesh.number("max_volume", obj.max_volume);
    spec.mesh = obj;
  } else {
    spec.mesh = TetMeshFile{type, read_mesh_file(mesh)};
  }
  mesh.finish();

  const JsonObject material = object.object("material");
  SoftBodyMaterial& m = spec.material;
  m.model = material.choice("model", m.model, {"neo_hookean", "st_venant_kirchhoff"});
  m.youngs_modulus = material.number("youngs_modulus");
  m.poisson_ratio = material.number("poisson_ratio");
  m.density = material.number("density");
  m.damping = material.number("damping", m.damping);
  m.volume_compliance = read_optional_number(material, "volume_compliance");
  material.finish();

  spec.collider_gap = object.number("collider_gap", spec.collider_gap);
  spec.angular_velocity = read_vector(object, "angular_velocity", spec.angular_velocity);
  if (const auto suction = object.optional_object("suction")) {
    SuctionSpec s;
    s.opening = to_vector3(suction->vec3("opening"));
    s.atmospheric_pressure = suction->number("atmospheric_pressure", s.atmospheric_pressure);
    s.seal_gap = suction->number("seal_gap", s.seal_gap);
    suction->finish();
    spec.suction = s;
  }
  read_particle_object_keys(object, spec);
  return spec;
}

namespace {

TetMesh make_soft_body_mesh(const SoftBodyMesh& spec, const SpecPlace& place, SceneBuildContext& ctx) {
  TetMesh out;
  std::string source = place.path();
  if (const auto* box = std::get_if<TetBox>(&spec)) {
    const Vec3 lo = place.vector("min", box->min), hi = place.vector("max", box->max);
    if (!((hi - lo).minCoeff() > 0)) place.fail("max", "max must exceed min along every axis");
    std::array<int, 3> cells;
    for (int a = 0; a < 3; ++a) cells[a] = place.integer("cells", box->cells[a], 1);
    const int per_cell = place.integer("tets_per_cell", box->tets_per_cell, 5, 6);
    check_memory(place, "cells", double(cells[0]) * cells[1] * cells[2] * per_cell, memory_cost::tetrahedron, "tetrahedra");
    out = make_box_tets(lo, hi, cells, per_cell == 5 ? CellSplit::five : CellSplit::six);
  } else if (const auto* file = std::get_if<TetMeshFile>(&spec)) {
    source = read_mesh_at(place, [&] { return resolve_path(ctx, file->file.file); });
    const bool gmsh = place.choice("type", file->format, {"msh", "tetgen"}) == "msh";
    // TetGen: a base name, read from <file>.node and <file>.ele.
    out = read_mesh_at(place, [&] { return gmsh ? read_gmsh_msh4(source) : read_tetgen(source + ".node", source + ".ele"); });
    place_vertices(file->file, place, out.vertices);
  } else if (const auto* obj = std::get_if<TetrahedralizedObj>(&spec)) {
    source = read_mesh_at(place, [&] { return resolve_path(ctx, obj->file.file); });
    const Real quality = place.number("quality", obj->quality, Range::closed(1.1, 10));
    const Real max_volume = place.number("max_volume", obj->max_volume, Range::non_negative());
    out = read_mesh_at(place, [&] { return tetrahedralize_obj(source, quality, max_volume); });
    place_vertices(obj->file, place, out.vertices);
  } else {
    const auto& list = std::get<TetList>(spec);
    for (const Vector3& v : list.vertices) out.vertices.push_back(place.vector("vertices", v));
    out.tets = checked_cells(list.tets, list.vertices.size(), place, "tets");
  }
  if (std::holds_alternative<TetList>(spec) || std::holds_alternative<TetBox>(spec)) {
    orient_and_validate_tets(out, source);
  } else {  // a mesh file's inverted or degenerate cells are reported at its "file" key
    read_mesh_at(place, [&] {
      orient_and_validate_tets(out, source);
      return 0;
    });
  }
  return out;
}

}  // namespace

void add_soft_body(const SoftBodySpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  const Index object_index = static_cast<Index>(m.objects.size());
  const TetMesh mesh = make_soft_body_mesh(spec.mesh, place.at("mesh"), ctx);

  const SoftBodyMaterial& mat = spec.material;
  const SpecPlace material = place.at("material");
  const Real youngs = material.required("youngs_modulus", mat.youngs_modulus, Range::positive());
  const Real poisson = material.required("poisson_ratio", mat.poisson_ratio, Range::open(-1, 0.5));
  const Real density = material.required("density", mat.density, Range::positive());
  const bool neo_hookean = material.choice("model", mat.model, {"neo_hookean", "st_venant_kirchhoff"}) == "neo_hookean";
  const Real damping = material.number("damping", mat.damping, Range::non_negative());
  const bool has_volume = mat.volume_compliance.has_value();
  const Real volume_compliance = material.number("volume_compliance", mat.volume_compliance.value_or(0), Range::non_negative());

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
  const Real radius =
      place.number("collision_radius", spec.collision_radius.value_or(0.5 * edge_sum / boundary_edges.size()), Range::positive());

  // Initial velocity: v + omega x (x - center of mass).
  const Vec3 velocity = place.vector("velocity", spec.velocity);
  const Vec3 omega = place.vector("angular_velocity", spec.angular_velocity);
  Vec3 com = Vec3::Zero();
  Real total = 0;
  for (size_t i = 0; i < masses.size(); ++i) {
    com += masses[i] * mesh.vertices[i];
    total += masses[i];
  }
  com /= total;
  // A solid's surface vertices lie on its surface: by default they touch colliders directly.
  const Real gap = place.number("collider_gap", spec.collider_gap, Range::non_negative());
  add_particles(ctx, info, mesh.vertices, masses, radius, gap, velocity);
  for (Index p = info.particle_begin; p < info.particle_end; ++p)
    ctx.initial_velocity[p] += omega.cross(m.particle_rest_position[p] - com);

  info.kind = ObjectKind::soft_body;
  info.self_collision = spec.self_collision;
  set_fluid_coupling(spec.fluid_coupling, spec.fluid_friction, place, info);
  set_contact_material(spec.contact, place, info);
  add_pins(spec.pin, place, info, ctx);

  const Index base = info.particle_begin;
  for (const auto& f : boundary) info.surface.push_back({base + f[0], base + f[1], base + f[2]});
  for (const auto& t : mesh.tets) {
    const std::array<Index, 4> g{base + t[0], base + t[1], base + t[2], base + t[3]};
    const std::array<Vec3, 4> rest{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]};
    info.tets.push_back(g);
    if (neo_hookean) m.family<NeoHookeanTetConstraints>().add(g, rest, youngs, poisson, damping, object_index);
    else m.family<GreenStrainTetConstraints>().add(g, rest, youngs, poisson, damping, object_index);
    if (has_volume) m.family<TetVolumeConstraints>().add(g, rest, volume_compliance, damping, object_index);
  }
  if (spec.suction) add_suction_cup(*spec.suction, place.at("suction"), mesh.vertices, boundary, base, object_index, m);
  // Only surface vertices can touch anything.
  std::vector<Index> surface_vertices;
  for (const auto& f : boundary) surface_vertices.insert(surface_vertices.end(), f.begin(), f.end());
  std::sort(surface_vertices.begin(), surface_vertices.end());
  surface_vertices.erase(std::unique(surface_vertices.begin(), surface_vertices.end()), surface_vertices.end());
  for (Index v : surface_vertices) m.contact_particle.push_back(base + v);
}

}  // namespace moreau
