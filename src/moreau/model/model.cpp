#include "moreau/model/model.hpp"

namespace moreau {

Index Model::find_object(const std::string& name) const {
  for (size_t i = 0; i < objects.size(); ++i)
    if (objects[i].name == name) return static_cast<Index>(i);
  return -1;
}

void Model::color_constraints() {
  for_each_family(constraints, [&](auto& family, int) { family.color(particle_inv_mass); });
}

}  // namespace moreau
