// "kind": "cloth": a triangle mesh with a membrane or edge springs, and dihedral or isometric
// bending.
#include <fmt/format.h>

#include <cmath>

#include "moreau/geometry/mesh_generators.hpp"
#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/scene/memory_estimate.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

ClothSpec read_cloth(const JsonObject& object) {
  ClothSpec spec;
  const JsonObject mesh = object.object("mesh");
  if (mesh.choice("type", {"grid", "obj"}) == "grid") {
    GridSheet grid;
    const Vec2 size = mesh.vec2("size", Range::any());
    grid.size = {size.x(), size.y()};
    const auto res = mesh.integers("resolution", 2, 2);
    grid.resolution = {res[0], res[1]};
    grid.center = read_vector(mesh, "center", grid.center);
    grid.rotation_deg = read_vector(mesh, "rotation_deg", grid.rotation_deg);
    spec.mesh = grid;
  } else {
    spec.mesh = read_mesh_file(mesh);
  }
  mesh.finish();

  const JsonObject material = object.object("material");
  ClothMaterial& m = spec.material;
  m.area_density = read_optional_number(material, "area_density");
  m.vertex_mass = read_optional_number(material, "vertex_mass");
  m.damping = material.number("damping", m.damping);
  m.youngs_modulus = read_optional_number(material, "youngs_modulus");
  m.poisson_ratio = read_optional_number(material, "poisson_ratio");
  m.thickness = read_optional_number(material, "thickness");
  m.stretch_compliance = read_optional_number(material, "stretch_compliance");
  m.bending_stiffness = read_optional_number(material, "bending_stiffness");
  m.bend_compliance = read_optional_number(material, "bend_compliance");
  if (material.has("bending_model")) m.bending_model = material.string("bending_model");
  material.finish();

  spec.collider_gap = read_optional_number(object, "collider_gap");
  read_particle_object_keys(object, spec);
  return spec;
}

namespace {

TriangleMesh make_cloth_mesh(const ClothMesh& spec, const SpecPlace& place, SceneBuildContext& ctx) {
  TriangleMesh out;
  if (const auto* grid = std::get_if<GridSheet>(&spec)) {
    const Vec2 size = place.pair("size", grid->size, Range::positive());
    const int nx = place.integer("resolution", grid->resolution[0], 2), nz = place.integer("resolution", grid->resolution[1], 2);
    const Vec3 center = place.vector("center", grid->center);
    check_memory(place, "resolution", double(nx) * nz, memory_cost::cloth_cell, "grid cells");
    out = make_grid_sheet(size, {nx, nz}, center);
    // Optional rotation about the sheet's centre (world x, then y, then z): a curtain is
    // "rotation_deg": [90, 0, 0].
    const Mat3 rotation = rotation_from_degrees(place.vector("rotation_deg", grid->rotation_deg));
    for (auto& v : out.vertices) v = center + rotation * (v - center);
  } else if (const auto* file = std::get_if<MeshFile>(&spec)) {
    out = read_mesh_at(place, [&] { return read_obj_triangles(resolve_path(ctx, file->file)); });
    place_vertices(*file, place, out.vertices);
  } else {
    const auto& list = std::get<TriangleList>(spec);
    for (const Vector3& v : list.vertices) out.vertices.push_back(place.vector("vertices", v));
    out.triangles = checked_cells(list.triangles, list.vertices.size(), place, "triangles");
  }
  for (size_t t = 0; t < out.triangles.size(); ++t) {
    const auto& k = out.triangles[t];
    const Real area2 = (out.vertices[k[1]] - out.vertices[k[0]]).cross(out.vertices[k[2]] - out.vertices[k[0]]).norm();
    if (!(area2 > 0)) place.fail("type", fmt::format("triangle {} of the cloth mesh is degenerate (zero area)", t));
  }
  return out;
}

}  // namespace

void add_cloth(const ClothSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  const Index object_index = static_cast<Index>(m.objects.size());
  const TriangleMesh mesh = make_cloth_mesh(spec.mesh, place.at("mesh"), ctx);

  const ClothMaterial& mat = spec.material;
  const SpecPlace material = place.at("material");
  // Mass: an area density (kg/m^2) lumped to the vertices, or one mass per vertex (kg), as
  // position-based libraries often give every particle.
  if (mat.area_density.has_value() == mat.vertex_mass.has_value())
    material.fail("area_density", "give the cloth's mass as either area_density (kg/m^2) or vertex_mass (kg per vertex)");
  const bool per_vertex = mat.vertex_mass.has_value();
  const Real area_density = per_vertex ? 0 : material.required("area_density", mat.area_density, Range::positive());
  const Real vertex_mass = per_vertex ? material.required("vertex_mass", mat.vertex_mass, Range::positive()) : 0;
  const Real damping = material.number("damping", mat.damping, Range::non_negative());
  const bool membrane = mat.youngs_modulus.has_value();
  Real youngs = 0, poisson = 0, thickness = 0;
  if (membrane) {
    youngs = material.required("youngs_modulus", mat.youngs_modulus, Range::positive());
    poisson = material.number("poisson_ratio", mat.poisson_ratio.value_or(0.3), Range::open(-1, 0.5));
    thickness = material.required("thickness", mat.thickness, Range::positive());
    if (mat.stretch_compliance)
      material.fail("stretch_compliance", "give either a membrane (youngs_modulus, poisson_ratio, thickness) or "
                                          "stretch_compliance, not both");
  } else if (mat.poisson_ratio || mat.thickness) {
    material.fail(mat.poisson_ratio ? "poisson_ratio" : "thickness",
                  "belongs to a membrane: give youngs_modulus too, or leave it out for edge springs");
  }
  const Real stretch_compliance = material.number("stretch_compliance", mat.stretch_compliance.value_or(0), Range::non_negative());
  if (mat.bending_stiffness && mat.bend_compliance)
    material.fail("bend_compliance", "give either bending_stiffness (N m) or bend_compliance (1/(N m)), not both");
  Real bending_stiffness = membrane ? youngs * thickness * thickness * thickness / (12 * (1 - poisson * poisson)) : 0;
  bending_stiffness = material.number("bending_stiffness", mat.bending_stiffness.value_or(bending_stiffness), Range::non_negative());
  const bool has_bend_compliance = mat.bend_compliance.has_value();
  const Real bend_compliance = material.number("bend_compliance", mat.bend_compliance.value_or(0), Range::non_negative());
  const bool isometric = material.choice("bending_model", mat.bending_model, {"dihedral", "isometric"}) == "isometric";

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
  const Real radius = place.number("collision_radius", spec.collision_radius.value_or(0.5 * mean_edge), Range::positive());

  // A sheet has no volume: it keeps `collider_gap` (default: its collision radius) from colliders.
  const Real gap = place.number("collider_gap", spec.collider_gap.value_or(radius), Range::non_negative());
  add_particles(ctx, info, mesh.vertices, masses, radius, gap, place.vector("velocity", spec.velocity));
  info.kind = ObjectKind::cloth;
  info.self_collision = spec.self_collision;
  set_fluid_coupling(spec.fluid_coupling, spec.fluid_friction, place, info);
  set_contact_material(spec.contact, place, info);
  add_pins(spec.pin, place, info, ctx);

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
