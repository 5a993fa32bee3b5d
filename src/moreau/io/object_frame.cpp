#include "moreau/io/object_frame.hpp"

#include <utility>

#include "moreau/collision/collider_surface.hpp"
#include "moreau/collision/shape_surface.hpp"
#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/io/continuum_frame.hpp"
#include "moreau/io/rod_frame.hpp"

namespace moreau {
namespace {

ObjectFrame triangle_frame(const TriangleMesh& mesh, std::vector<VtkPointArray> vectors) {
  ObjectFrame f{.cells = ObjectFrame::Cells::triangles, .points = mesh.vertices, .surface = mesh.triangles,
                .point_vectors = std::move(vectors)};
  for (const auto& t : mesh.triangles) f.connectivity.insert(f.connectivity.end(), t.begin(), t.end());
  return f;
}

// Live particles of one fluid phase: position, velocity, density, pressure, stable id, radius;
// with heat (fluid_heat.hpp) also temperature and liquid fraction; a gas (ambient_air.hpp) also its
// smoke concentration.
ObjectFrame fluid_frame(const Model& model, const ObjectInfo& object, const FluidState& fluid) {
  const FluidPhase& phase = model.fluid.phases[object.fluid_phase];
  std::vector<Vec3> x, v;
  std::vector<Real> density, pressure, id, temperature, liquid_fraction, smoke;
  for (Index i = 0; i < fluid.count; ++i) {
    if (fluid.phase[i] != object.fluid_phase) continue;
    x.push_back(fluid.position[i]);
    v.push_back(fluid.velocity[i]);
    density.push_back(fluid.density[i]);
    pressure.push_back(fluid.pressure[i]);
    id.push_back(fluid.id[i]);
    if (model.fluid.thermal) {
      temperature.push_back(fluid_temperature(phase, fluid.enthalpy[i]));
      liquid_fraction.push_back(fluid_liquid_fraction(phase, fluid.enthalpy[i]));
    }
    if (phase.gas) smoke.push_back(fluid.smoke[i]);
  }
  const std::size_t n = x.size();
  ObjectFrame f{.points = std::move(x),
                .point_vectors = {{"velocity", std::move(v)}},
                .point_scalars = {{"density", std::move(density)},
                                  {"pressure", std::move(pressure)},
                                  {"id", std::move(id)},
                                  {"radius", std::vector<Real>(n, model.fluid.particle_radius)}}};
  if (model.fluid.thermal) {
    f.point_scalars.push_back({"temperature", std::move(temperature)});
    f.point_scalars.push_back({"liquid_fraction", std::move(liquid_fraction)});
  }
  if (phase.gas) f.point_scalars.push_back({"smoke", std::move(smoke)});
  return f;
}

// Grains or shape-matched particles: position, velocity, displacement and radius; grains also
// their angular velocity and, with settings.sleep, whether each sleeps (1) or not (0). The grains
// an emitter has not released (the object's last, model/particle_emitter.hpp) are left out.
ObjectFrame grain_frame(const Model& model, const ObjectInfo& object, const State& state) {
  const Index b = object.particle_begin;
  Index n = object.particle_count();
  while (n > 0 && !state.live(b + n - 1)) --n;
  std::vector<Vec3> x(state.position.begin() + b, state.position.begin() + b + n);
  std::vector<Vec3> v(state.velocity.begin() + b, state.velocity.begin() + b + n), u(n);
  for (Index i = 0; i < n; ++i) u[i] = x[i] - model.particle_rest_position[b + i];
  ObjectFrame f{.points = std::move(x), .point_vectors = {{"velocity", std::move(v)}, {"displacement", std::move(u)}}};
  f.point_scalars.push_back(
      {"radius", std::vector<Real>(model.particle_radius.begin() + b, model.particle_radius.begin() + b + n)});
  if (model.settings.sleep.enabled && object.kind == ObjectKind::granular) {
    std::vector<Real> asleep(n);
    for (Index i = 0; i < n; ++i) asleep[i] = state.sleep.asleep(b + i) ? 1 : 0;
    f.point_scalars.push_back({"asleep", std::move(asleep)});
  }
  if (object.kind == ObjectKind::granular)
    f.point_vectors.push_back(
        {"angular_velocity", std::vector<Vec3>(state.angular_velocity.begin() + b, state.angular_velocity.begin() + b + n)});
  return f;
}

// A rigid body's surface in the world, with the velocity of each surface point.
ObjectFrame rigid_frame(const Model& model, const ObjectInfo& object, const State& state) {
  const Index b = object.body;
  TriangleMesh mesh = shape_surface(model.rigid.body_shape[b]);
  const Quat& q = state.rigid.orientation[b];
  std::vector<Vec3> velocity(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3 r = q * mesh.vertices[i];
    mesh.vertices[i] = state.rigid.position[b] + r;
    velocity[i] = state.rigid.velocity[b] + state.rigid.angular_velocity[b].cross(r);
  }
  return triangle_frame(mesh, {{"velocity", std::move(velocity)}});
}

// A collider's surface at the frame's time; a removed collider (`until`) has none, so the series
// keeps its files. A container's (`inside`) triangles face into it, where its contents are, so a
// viewer that culls back faces sees into a tank.
ObjectFrame collider_frame(const Model& model, const ObjectInfo& object, const State& state, Real plane_half_size) {
  const Collider& collider = model.colliders[object.collider];
  TriangleMesh mesh =
      collider.present_at(state.time) ? collider_surface(collider, state.time, plane_half_size) : TriangleMesh{};
  if (collider.inside)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return triangle_frame(mesh, {{"velocity", std::vector<Vec3>(mesh.vertices.size(), collider.velocity)}});
}

// Cloth (its triangles) or a soft body (its tetrahedra, and its boundary as the surface), with
// velocity and displacement from the rest position.
ObjectFrame particle_mesh_frame(const Model& model, const ObjectInfo& object, const State& state) {
  const Index b = object.particle_begin, n = object.particle_count();
  std::vector<Vec3> x(state.position.begin() + b, state.position.begin() + b + n);
  std::vector<Vec3> v(state.velocity.begin() + b, state.velocity.begin() + b + n), u(n);
  for (Index i = 0; i < n; ++i) u[i] = x[i] - model.particle_rest_position[b + i];
  ObjectFrame f{.points = std::move(x), .point_vectors = {{"velocity", std::move(v)}, {"displacement", std::move(u)}}};
  for (const auto& t : object.surface) f.surface.push_back({t[0] - b, t[1] - b, t[2] - b});
  if (object.kind == ObjectKind::soft_body) {
    f.cells = ObjectFrame::Cells::tetrahedra;
    for (const auto& t : object.tets)
      for (Index p : t) f.connectivity.push_back(p - b);
  } else {
    f.cells = ObjectFrame::Cells::triangles;
    for (const auto& t : f.surface) f.connectivity.insert(f.connectivity.end(), t.begin(), t.end());
  }
  return f;
}

}  // namespace

ObjectFrame object_frame(const Model& model, const ObjectInfo& object, const State& state, Real plane_half_size) {
  switch (object.kind) {
    case ObjectKind::fluid: return fluid_frame(model, object, state.fluid);
    case ObjectKind::granular:
    case ObjectKind::shape_matched: return grain_frame(model, object, state);
    case ObjectKind::continuum: return continuum_frame(model, object, state);
    case ObjectKind::rod: return rod_frame(model, model.rods[object.rod], state);
    case ObjectKind::rigid_body: return rigid_frame(model, object, state);
    case ObjectKind::collider: return collider_frame(model, object, state, plane_half_size);
    default: return particle_mesh_frame(model, object, state);
  }
}

}  // namespace moreau
