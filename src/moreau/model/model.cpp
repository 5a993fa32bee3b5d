#include "moreau/model/model.hpp"

namespace moreau {

Index Model::find_object(const std::string& name) const {
  for (size_t i = 0; i < objects.size(); ++i)
    if (objects[i].name == name) return static_cast<Index>(i);
  return -1;
}

Index Model::initial_particle_end(Index object) const {
  for (const ParticleEmitter& e : particle_emitters)
    if (e.object == object) return e.first;
  return objects[object].particle_end;
}

void Model::color_constraints() {
  for_each_family(constraints, [&](auto& family, int) { family.color(particle_inv_mass); });
}

}  // namespace moreau
