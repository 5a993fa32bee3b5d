#pragma once
// Builders that turn one scene object into particles, constraints and colliders of the model.
// Shared between scene_loader.cpp and the per-kind build_*.cpp files; not part of the public API.
#include <filesystem>
#include <vector>

#include "moreau/model/model.hpp"
#include "moreau/scene/json_reader.hpp"

namespace moreau {

/// What the builders add to besides the model: per-particle initial velocities, and the directory
/// that relative mesh paths are resolved against.
struct SceneBuildContext {
  Model& model;
  std::vector<Vec3>& initial_velocity;
  std::filesystem::path scene_directory;
  Real duration = 0;  // s, settings.duration of the scene file (emitters stop there by default)
};

void build_collider(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx);
void build_cloth(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx);
void build_soft_body(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx);
void build_fluid(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx);
void build_rigid_body(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx);
/// After all objects: colliders become kinematic bodies for the rigid bodies to collide with.
void add_colliders_as_bodies(Model& model);
/// The scene's "joints" list.
void build_joints(const std::vector<JsonObject>& joints, Model& model);
/// After all objects: samples collider walls for the fluids and sets the derived fluid constants.
void finish_fluids(Model& model);

/// Rotation from "rotation_deg": [rx, ry, rz], applied about the world x, then y, then z axes.
Mat3 rotation_from_degrees(const Vec3& degrees);

/// "friction": a number (static = dynamic) or {"static": mu_s, "dynamic": mu_k}; and "restitution".
void read_contact_material(const JsonObject& object, Real& mu_static, Real& mu_dynamic, Real& restitution);

/// Appends the object's particles: rest positions and masses (kg) per vertex.
void add_particles(SceneBuildContext& ctx, ObjectInfo& info, const std::vector<Vec3>& positions,
                   const std::vector<Real>& masses, Real radius, Real collider_gap, const Vec3& velocity);

/// "pin": a list of regions ({"box": {min, max}}, {"sphere": {center, radius}} or
/// {"vertices": [...]}, each with an optional "compliance" in m/N). Rigid pins zero the inverse
/// mass; compliant pins add attachment constraints.
void read_pins(const JsonObject& object, const ObjectInfo& info, SceneBuildContext& ctx);

/// Resolves a mesh path relative to the scene file.
std::string resolve_path(const SceneBuildContext& ctx, const std::string& path);

}  // namespace moreau
