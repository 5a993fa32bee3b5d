// The run loop's engine list: which engine steps a scene.
#include "moreau/run/engines.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {

std::unique_ptr<Engine> make_engine(Scene& scene) {
  if (!scene.fem) return make_constraint_engine(scene);
  if (scene.fem->flow) return make_flow_engine(scene);
  return make_solid_engine(scene);
}

}  // namespace moreau
