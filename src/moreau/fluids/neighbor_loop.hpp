#pragma once
// The scalar loop over a fluid particle's neighbours closer than the kernel support h (the lists
// also hold pairs in the skin beyond h). The solver's hot pair loops use pair_chunks.hpp instead.
#include <cmath>

#include "moreau/fluids/fluid_state.hpp"
#include "moreau/fluids/sph_kernel.hpp"

namespace moreau {

/// Calls visit(j, r, g) for every fluid neighbour j of particle k within h, with r = x_k - x_j and
/// g = (dW/dr) / |r| (grad W = g r).
template <class Visit>
void for_each_fluid_neighbor(const FluidState& fluid, const CubicSplineKernel& kernel, Index k, Visit&& visit) {
  const Vec3 xk = fluid.position[k];
  const Index* row = fluid.fluid_neighbors.row(k);
  for (Index n = 0; n < fluid.fluid_neighbors.count[k]; ++n) {
    const Index j = row[n];
    const Vec3 r = xk - fluid.position[j];
    const Real d2 = r.squaredNorm();
    if (d2 >= kernel.h2) continue;
    visit(j, r, kernel.gradient_factor(std::sqrt(d2)));
  }
}

}  // namespace moreau
