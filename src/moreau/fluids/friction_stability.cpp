#include "moreau/fluids/friction_stability.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/model/model.hpp"

namespace moreau {

namespace {

// Mass and area of the object's surface triangles (ObjectInfo::surface, at rest): a cloth's every
// vertex and triangle, a soft body's boundary vertices and faces.
Real triangle_surface_density(const Model& model, const ObjectInfo& object) {
  std::vector<Index> vertices;
  Real area = 0;
  for (const auto& t : object.surface) {
    const Vec3& a = model.particle_rest_position[t[0]];
    area += 0.5 * (model.particle_rest_position[t[1]] - a).cross(model.particle_rest_position[t[2]] - a).norm();
    vertices.insert(vertices.end(), t.begin(), t.end());
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  Real mass = 0;
  for (Index p : vertices) mass += model.particle_mass[p];
  return area > 0 ? mass / area : 0;
}

}  // namespace

std::vector<GrippingSolid> light_gripping_solids(const Model& model, Real h) {
  // rho0 sqrt(nu h) of the heaviest drag any fluid of the scene puts on a surface.
  Real dragged = 0;
  for (const FluidPhase& phase : model.fluid.phases) {
    dragged = std::max(dragged, phase.rest_density * std::sqrt(largest_viscosity(phase) * h));
  }
  std::vector<GrippingSolid> light;
  for (const ObjectInfo& object : model.objects) {
    if (object.fluid_friction <= 0 || !object.has_particles()) continue;
    bool free = false;
    for (Index p = object.particle_begin; p < object.particle_end && !free; ++p) free = model.particle_inv_mass[p] > 0;
    if (!free) continue;
    Real density = 0;
    if (object.kind == ObjectKind::continuum)
      density = model.particle_mass[object.particle_begin] / (model.continuum.spacing * model.continuum.spacing);
    else
      density = triangle_surface_density(model, object);
    if (density > 0 && density < dragged) light.push_back({object.name, density, dragged});  // 0: no surface
  }
  return light;
}

}  // namespace moreau
