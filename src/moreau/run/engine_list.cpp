// The run loop's engine list: which engine steps a scene.
#include <fmt/format.h>

#include "moreau/errors.hpp"
#include "moreau/fem/distributed/mpi_ranks.hpp"
#include "moreau/run/engines.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {

std::unique_ptr<Engine> make_engine(Scene& scene) {
  if (!scene.fem) {
    // The constraint engine's steps are not divided among processes: under mpirun every rank
    // would repeat the whole run.
    if (mpi_ranks() > 1)
      throw InputError(fmt::format(
          "{}: settings.solver: \"{}\" runs on one process; a run on {} MPI ranks is for FEM scenes (\"solver\": "
          "\"fem\") solved with \"linear_solver\": {{\"type\": \"petsc\"}}: run this scene without mpirun",
          scene.file, scene.solver, mpi_ranks()));
    return make_constraint_engine(scene);
  }
  if (scene.fem->flow) return make_flow_engine(scene);
  return make_solid_engine(scene);
}

}  // namespace moreau
