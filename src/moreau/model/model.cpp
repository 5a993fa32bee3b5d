#include "moreau/model/model.hpp"

namespace moreau {

Index Model::find_object(const std::string& name) const {
  for (size_t i = 0; i < objects.size(); ++i)
    if (objects[i].name == name) return static_cast<Index>(i);
  return -1;
}

void Model::color_constraints() {
  distance.color(particle_inv_mass);
  bending.color(particle_inv_mass);
  isometric_bending.color(particle_inv_mass);
  triangle_strain.color(particle_inv_mass);
  neo_hookean.color(particle_inv_mass);
  tet_volume.color(particle_inv_mass);
}

}  // namespace moreau
