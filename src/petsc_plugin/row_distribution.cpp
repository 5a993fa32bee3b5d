#include "row_distribution.hpp"

#include <stdexcept>
#include <string>

namespace moreau::petsc_plugin {

RowDistribution::RowDistribution(const std::vector<int>& owner, int rank, int ranks) {
  std::vector<PetscInt> start(static_cast<size_t>(ranks) + 1, 0);
  for (int o : owner) {
    if (o < 0 || o >= ranks)
      throw std::invalid_argument("an unknown is owned by rank " + std::to_string(o) + " of " + std::to_string(ranks));
    ++start[static_cast<size_t>(o) + 1];
  }
  for (int r = 0; r < ranks; ++r) start[r + 1] += start[r];
  first = start[rank];
  this->rank = rank;
  petsc_index.resize(owner.size());
  for (size_t i = 0; i < owner.size(); ++i) {
    petsc_index[i] = start[owner[i]]++;
    if (owner[i] == rank) owned.push_back(static_cast<int>(i));
  }
}

}  // namespace moreau::petsc_plugin
