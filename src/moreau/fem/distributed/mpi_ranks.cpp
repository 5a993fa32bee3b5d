#include "moreau/fem/distributed/mpi_ranks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "moreau/fem/petsc/petsc_plugin_loader.hpp"

namespace moreau {

namespace {
const petsc_plugin::Communicator* world = nullptr;  // set once, before any scene is loaded
}

int launched_ranks() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* value = std::getenv(variable); value && *value) {
      char* end = nullptr;
      const long ranks = std::strtol(value, &end, 10);
      if (*end == '\0' && ranks >= 1 && ranks < (1L << 24)) return static_cast<int>(ranks);
    }
  return 1;
}

void start_mpi_if_launched() {
  const int launched = launched_ranks();
  if (launched <= 1 || world) return;
  const petsc_plugin::Communicator& started = petsc_backend().world();
  if (started.size() != launched)
    throw std::runtime_error(fmt::format(
        "mpirun started {} processes, but MPI's world in the PETSc plugin has {}: the mpirun used must be the one "
        "of the MPI that PETSc was built with (Open MPI on Debian)",
        launched, started.size()));
  world = &started;
}

const petsc_plugin::Communicator* mpi_world() { return world; }
int mpi_rank() { return world ? world->rank() : 0; }
int mpi_ranks() { return world ? world->size() : 1; }

int largest_over_ranks(int value) {
  if (!world) return value;
  const std::vector<int> ones(static_cast<size_t>(world->size()), 1);
  std::vector<double> values(ones.size());
  const double mine = value;
  world->all_gather(&mine, ones.data(), values.data());
  return static_cast<int>(*std::max_element(values.begin(), values.end()));
}

}  // namespace moreau
