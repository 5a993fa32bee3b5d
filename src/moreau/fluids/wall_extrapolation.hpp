#pragma once
// The wall samples of a fluid particle that carry a value held at a collider's surface: a no-slip
// wall's velocity (fluid_viscosity.hpp), a heated or cooled wall's temperature (fluid_heat.hpp).
// The sample, r behind the surface (boundary_sampling.hpp), takes the value that extrapolates the
// particle's linearly through the surface (Morris, Fox & Zhu 1997, sec. 3.3):
//   u_k - u_b  ->  beta (u_k - u_c),  beta = 1 + r / max(d_k, r),
// with u_c the wall's value and d_k the particle's distance from the surface.
#include <algorithm>
#include <cmath>

#include "moreau/fluids/fluid_state.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

/// Calls visit(b, collider, r, d2, beta) for every wall sample b within the kernel support of
/// fluid particle k whose collider passes accept(collider), with r = x_k - x_b and d2 = |r|^2.
template <class Accept, class Visit>
void for_each_extrapolated_wall_sample(const Model& model, const FluidState& fluid, Index k, Accept&& accept,
                                       Visit&& visit) {
  const FluidModel& fm = model.fluid;
  const FluidBoundarySamples& samples = fm.boundary;
  const Real h2 = fm.kernel.h2, depth = fm.particle_radius;
  const Vec3 xk = fluid.position[k];
  Index cached_collider = -1;
  Real distance = 0;  // m, of x_k from the cached collider's surface
  const Index* walls = fluid.boundary_neighbors.row(k);
  for (Index n = 0; n < fluid.boundary_neighbors.count[k]; ++n) {
    const Index b = walls[n];
    const Collider& c = model.colliders[samples.collider[b]];
    if (!accept(c)) continue;
    const Vec3 r = xk - fluid.boundary_position[b];
    const Real d2 = r.squaredNorm();
    if (d2 >= h2) continue;
    if (samples.collider[b] != cached_collider) {
      cached_collider = samples.collider[b];
      distance = collider_distance(c, fluid.boundary_position[b] - samples.local_position[b], xk).distance;
    }
    visit(b, c, r, d2, 1 + depth / std::max(distance, depth));
  }
}

}  // namespace moreau
