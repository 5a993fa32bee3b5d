#include "moreau/constraints/constraint_batches.hpp"

#include <bitset>

namespace moreau {

std::vector<Index> color_constraints(const std::vector<std::array<Index, 4>>& stencils,
                                     const std::vector<Real>& particle_inv_mass, ColorBatches& batches) {
  // Colours used so far at each particle. Beyond kMaxColors a constraint goes to an extra colour
  // of its own kind: colour index kMaxColors + n for the n-th overflow round.
  constexpr int kMaxColors = 256;
  std::vector<std::bitset<kMaxColors>> used(particle_inv_mass.size());
  std::vector<int> color(stencils.size(), 0);
  int color_count = 0;
  for (size_t k = 0; k < stencils.size(); ++k) {
    std::bitset<kMaxColors> taken;
    for (Index p : stencils[k])
      if (p >= 0 && particle_inv_mass[p] > 0) taken |= used[p];
    int c = 0;
    while (c < kMaxColors && taken.test(c)) ++c;
    if (c == kMaxColors) {
      c = kMaxColors;  // rare: park it in a trailing colour and split that colour serially below
    } else {
      for (Index p : stencils[k])
        if (p >= 0 && particle_inv_mass[p] > 0) used[p].set(c);
    }
    color[k] = c;
    color_count = std::max(color_count, c + 1);
  }

  // Stable counting sort by colour keeps the original order inside a colour (determinism).
  std::vector<Index> permutation;
  permutation.reserve(stencils.size());
  batches.offsets.assign(1, 0);
  for (int c = 0; c < color_count; ++c) {
    for (size_t k = 0; k < stencils.size(); ++k)
      if (color[k] == c) {
        if (c == kMaxColors) batches.offsets.push_back(static_cast<Index>(permutation.size()));
        permutation.push_back(static_cast<Index>(k));
      }
    if (c < kMaxColors) batches.offsets.push_back(static_cast<Index>(permutation.size()));
  }
  if (color_count > kMaxColors) batches.offsets.push_back(static_cast<Index>(permutation.size()));
  // Remove empty batches (they cost a barrier each).
  batches.offsets.erase(std::unique(batches.offsets.begin(), batches.offsets.end()), batches.offsets.end());
  return permutation;
}

}  // namespace moreau
