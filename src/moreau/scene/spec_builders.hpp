#pragma once
// The scene builder's two halves, one pair per spec (build_<kind>.cpp, build_joints.cpp,
// build_probe.cpp, build_settings.cpp):
//   read_<kind>  scene JSON -> spec (scene_builder.hpp): types, required keys, and the file
//                format's alternatives (a box's "size" for "half_extents", "offset" for a plane
//                point); no physics is checked here;
//   add_<kind>   spec -> model: every range and consistency check, reported at the spec's place,
//                then the particles, constraints, bodies and colliders.
// A scene file and a SceneBuilder in code both end in the add_ functions (scene_assembly.cpp).
// Not part of the public API.
#include <filesystem>
#include <functional>
#include <vector>

#include "moreau/io/frame_formats.hpp"
#include "moreau/model/model.hpp"
#include "moreau/scene/json_reader.hpp"
#include "moreau/scene/spec_place.hpp"
#include "moreau/scene_builder.hpp"

namespace moreau {

struct Probe;
struct Scene;

/// What the adders add to besides the model: per-particle initial velocities, and the directory
/// that relative mesh paths are resolved against.
struct SceneBuildContext {
  Model& model;
  std::vector<Vec3>& initial_velocity;
  std::filesystem::path scene_directory;
  Real duration = 0;  // s, settings.duration (emitters stop there by default)
};

ColliderSpec read_collider(const JsonObject& object);
ClothSpec read_cloth(const JsonObject& object);
SoftBodySpec read_soft_body(const JsonObject& object);
FluidSpec read_fluid(const JsonObject& object);
RigidBodySpec read_rigid_body(const JsonObject& object);
RodSpec read_rod(const JsonObject& object);
GranularSpec read_granular(const JsonObject& object);
ShapeMatchedSpec read_shape_matched(const JsonObject& object);
ContinuumSpec read_continuum(const JsonObject& object);
JointSpec read_joint(const JsonObject& joint);
ProbeSpec read_probe(const JsonObject& probe);
/// "settings" of a constraint-engine scene.
SceneSettings read_settings(const JsonObject& settings);
/// settings -> the scene's solver settings, duration and output.
void apply_settings(const SceneSettings& spec, const SpecPlace& place, Scene& scene);
/// "settings.output": every N steps, and the formats.
/// `surfaces_and_points`: the engine also writes "obj" and "ply" (the constraint engine), not only "vtk".
void read_output_settings(const JsonObject& settings, int& every, FrameFormats& formats, int& checkpoint_every,
                          bool surfaces_and_points);

void add_collider(const ColliderSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
void add_cloth(const ClothSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
void add_soft_body(const SoftBodySpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
/// The soft body's cavity and rim (its boundary faces `boundary` over `rest`, numbered from `base`).
void add_suction_cup(const SuctionSpec& spec, const SpecPlace& place, const std::vector<Vec3>& rest,
                     const std::vector<std::array<Index, 3>>& boundary, Index base, Index object, Model& model);
void add_fluid(const FluidSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
void add_rigid_body(const RigidBodySpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
/// The rod's segments (rigid bodies), its junctions and end conditions (joints).
void add_rod(const RodSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
/// The grains: particles on a lattice in the blocks, all of them in the particle contacts.
void add_granular(const GranularSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
void add_shape_matched(const ShapeMatchedSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
/// The continuum's particles on a lattice of its spacing, its material and its rest volumes.
void add_continuum(const ContinuumSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx);
/// After all objects and joints: colliders become kinematic bodies for the rigid bodies.
void add_colliders_as_bodies(Model& model);
/// After all objects: one joint (pairs_without_contact is sorted by finish_joints).
void add_joint(const JointSpec& spec, const SpecPlace& place, Model& model);
void finish_joints(Model& model);
/// After all objects: samples collider walls for the fluids (refusing walls whose samples would
/// not fit in memory, at `object_place` of the collider) and sets the derived fluid constants.
void finish_fluids(Model& model, const std::function<SpecPlace(Index object)>& object_place);
/// The fluids' "interfacial_tension" entries, once every object is added: each names another liquid
/// of the scene, and a pair of liquids is given one tension (build_fluid_interfaces.cpp).
void add_fluid_interfaces(const std::vector<ObjectSpec>& objects, Model& model,
                          const std::function<SpecPlace(Index object)>& object_place);
/// A probe bound to the model's objects, particles and joints.
Probe bind_probe(const ProbeSpec& spec, const SpecPlace& place, const Model& model);

// ---- Shared by the readers ----
Vector3 read_vector(const JsonObject& object, const std::string& key, const Vector3& fallback);
std::optional<Vector3> read_optional_vector(const JsonObject& object, const std::string& key);
std::optional<double> read_optional_number(const JsonObject& object, const std::string& key);
std::optional<Vector2> read_optional_pair(const JsonObject& object, const std::string& key);
/// An "emitter" {"shape", "center", "direction", ...} of a fluid ("flow_rate", m^3/s) or a
/// granular object ("mass_rate", kg/s); the object's builder refuses the other one's rate.
EmitterSpec read_emitter(const JsonObject& e);
/// An emitter's opening (lattice points of spacing d about its centre) and window, checked.
struct EmitterOpening {
  Vec3 center = Vec3::Zero(), normal = Vec3::UnitY();  // m; the unit flow direction
  std::vector<Vec3> points;                             // m, relative to the centre
  Real start = 0, stop = 0;                             // s
};
/// `spacing_name` names d in messages ("particle spacing 2r"); stop defaults to the scene's duration.
EmitterOpening place_emitter_opening(const EmitterSpec& spec, const SpecPlace& e, Real d, const std::string& spacing_name,
                                     Real scene_duration);
/// The layers released from start to stop at `speed` (m/s), each d further on; at most 5e7
/// particles in all.
Index emitter_layers(const EmitterOpening& opening, const SpecPlace& e, Real speed, Real d);
/// A grain or continuum emitter at `opening` with layers d apart: its centre, direction, start,
/// the points of a layer and how far from the axis they reach (plus `max_radius`, the radius a
/// particle in the way is taken to have beyond its own). Speed, layers, object and first particle
/// are the caller's.
ParticleEmitter particle_emitter_at(const EmitterOpening& opening, Real d, Real max_radius);
/// A box {"min": [x, y, z], "max": [x, y, z]} in m (fluid, granular and shape-matched blocks).
FluidBlock read_block(const JsonObject& block);
/// An integer of any value an int holds (the adder checks its range).
int read_integer(const JsonObject& object, const std::string& key);
/// "friction": a number (static = dynamic) or {"static": mu_s, "dynamic": mu_k}; and "restitution".
ContactMaterial read_contact_material(const JsonObject& object);
/// "pin": a list of regions ({"box": {min, max}}, {"sphere": {center, radius}} or
/// {"vertices": [...]}, each with an optional "compliance" in m/N and "damping").
std::vector<PinSpec> read_pins(const JsonObject& object);
/// The keys cloth and soft bodies share: collision_radius, velocity, self_collision,
/// fluid_coupling, fluid_friction, the contact material and the pins.
template <class ParticleObjectSpec>
void read_particle_object_keys(const JsonObject& object, ParticleObjectSpec& spec) {
  spec.collision_radius = read_optional_number(object, "collision_radius");
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  spec.self_collision = object.boolean("self_collision", spec.self_collision);
  spec.fluid_coupling = object.boolean("fluid_coupling", spec.fluid_coupling);
  spec.fluid_friction = object.number("fluid_friction", spec.fluid_friction);
  spec.contact = read_contact_material(object);
  spec.pin = read_pins(object);
}
/// What a granular object or a continuum fills: "blocks", vertical "cylinders", "spheres" and a
/// closed OBJ "mesh" (its path).
inline FilledRegions read_filled_regions(const JsonObject& object) {
  FilledRegions spec;
  for (const JsonObject& block : object.object_list("blocks")) spec.blocks.push_back(read_block(block));
  for (const JsonObject& cylinder : object.object_list("cylinders")) {
    spec.cylinders.push_back({to_vector3(cylinder.vec3("base")), cylinder.number("radius"), cylinder.number("height")});
    cylinder.finish();
  }
  for (const JsonObject& sphere : object.object_list("spheres")) {
    spec.spheres.push_back({to_vector3(sphere.vec3("center")), sphere.number("radius")});
    sphere.finish();
  }
  if (object.has("mesh")) spec.mesh = object.string("mesh");
  if (object.has("mesh") && spec.mesh.empty()) object.fail("mesh", "give the path of a closed OBJ surface");
  return spec;
}
/// A cloth or soft-body "mesh" read from a file: "file", "scale", "translate".
MeshFile read_mesh_file(const JsonObject& mesh);

// ---- Shared by the adders ----
/// Rotation from "rotation_deg": [rx, ry, rz], applied about the world x, then y, then z axes.
Mat3 rotation_from_degrees(const Vec3& degrees);
/// The contact material, checked, as the object's (ObjectInfo::static_friction, ...).
void set_contact_material(const ContactMaterial& contact, const SpecPlace& place, ObjectInfo& info);
/// The object's fluid_coupling and its `fluid_friction` in [0, 1], checked (a wall friction needs the
/// coupling's samples to act at), as ObjectInfo::fluid_coupling and ::fluid_friction.
void set_fluid_coupling(bool coupling, double friction, const SpecPlace& place, ObjectInfo& info);
/// Mesh cells (triangles, tetrahedra) given in code: every index names one of `vertex_count`
/// vertices, and there is at least one cell.
template <size_t N>
std::vector<std::array<Index, N>> checked_cells(const std::vector<std::array<int, N>>& cells, size_t vertex_count,
                                                const SpecPlace& place, const std::string& field) {
  std::vector<std::array<Index, N>> out;
  for (const auto& cell : cells) {
    std::array<Index, N> c;
    for (size_t k = 0; k < N; ++k) {
      if (cell[k] < 0 || static_cast<size_t>(cell[k]) >= vertex_count)
        place.fail(field, "vertex " + std::to_string(cell[k]) + " does not exist; the mesh has " +
                              std::to_string(vertex_count) + " vertices");
      c[k] = cell[k];
    }
    out.push_back(c);
  }
  if (out.empty()) place.fail(field, "the mesh needs at least one cell");
  return out;
}
/// Appends the object's particles: rest positions and masses (kg) per vertex.
void add_particles(SceneBuildContext& ctx, ObjectInfo& info, const std::vector<Vec3>& positions,
                   const std::vector<Real>& masses, Real radius, Real collider_gap, const Vec3& velocity);
/// Rigid pins zero the inverse mass; compliant pins add attachment constraints.
void add_pins(const std::vector<PinSpec>& pins, const SpecPlace& place, const ObjectInfo& info, SceneBuildContext& ctx);
/// Resolves a mesh path relative to the scene file.
std::string resolve_path(const SceneBuildContext& ctx, const std::string& path);
/// Runs `read` (a mesh file reader) and reports what it refuses at the place's "file" key, so that
/// the message names the scene file and JSON path as well as the mesh file.
template <class Read>
auto read_mesh_at(const SpecPlace& place, Read&& read) {
  try {
    return read();
  } catch (const InputError& e) {
    place.fail("file", e.what());
  }
}
/// A closed OBJ surface whose inside is filled (fluids, grains), with its bounding box (m).
struct ClosedSurface {
  TriangleMesh mesh;
  Vec3 lo, hi;
};
/// Reads one; read errors fail at `field`.
ClosedSurface read_closed_surface(const SceneBuildContext& ctx, const SpecPlace& place, const std::string& field,
                                  const std::string& file);
/// A mesh file's vertices, scaled then translated.
void place_vertices(const MeshFile& file, const SpecPlace& place, std::vector<Vec3>& vertices);

}  // namespace moreau
