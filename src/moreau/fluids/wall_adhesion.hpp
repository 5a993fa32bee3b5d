#pragma once
// Wetting: a liquid's adhesion to the collider walls, set by its contact angle theta. Without it a
// wall meets the liquid as air does: the surface tension (surface_tension.hpp) rounds the liquid
// off against it, a contact angle of 180 degrees. Young and Dupre's relation gives the energy per
// wetted area that a wall of contact angle theta saves, the work of adhesion
//   W_a = gamma (1 + cos theta)   (N/m; 0 at 180 degrees, 2 gamma, the liquid's own, at 0),
// and this stage gives it to the liquid as a potential in the distance z from each collider surface:
//   U(z) = -W_a (2r)^2 psi(z),   psi(z) = c (1 - z / z_a)^2 for z < z_a = 5r, 0 beyond,
// (2r)^2 the wall area a lattice particle covers. The particles are kept z >= r from a wall, so a
// column of lattice layers over the wall, at z = r, 3r, (5r), has psi summing to c (0.64 + 0.16) = 1
// with c = 1.25: the column's energy is -W_a per area, Young-Dupre's. The range reaches the second
// layer on purpose: a wall that pulled the first layer only would press it against itself, and
// nothing would draw the liquid over the edge of the wetted patch (the contact line would stay
// where it is). The force -dU/dz points into the wall,
//   F = -k W_a (2r)^2 2c (1 - z / z_a) / z_a  n     (n the wall's normal into the liquid; k below),
// applied to the velocities once per step after the surface tension; every collider in reach
// adds its own (a corner draws from both walls). The walls take no reaction.
//
// Calibration. With W_a as above, drops settled at angles 12-40 degrees larger than theta (112 for
// 90, 132 for 120, 100 for 60). Why is not established: most likely the particles' wall does not
// cost the liquid exactly gamma, as the air it stands for would, or the discrete contact line is
// held back where Young's balance lets it move. The wall therefore draws with k W_a, k = 1.7, the
// factor that put a 1 cm drop's cap at
// 94.4, 56.6 and 118.5 degrees for 90, 60 and 120 at r = 0.5 mm, and at 89.6, 56.4 and 116.2 at
// r = 0.35 mm (tests/fluids/test_fluid_wetting.cpp; docs/validation.md). Near complete wetting it
// spreads too far: 17 degrees for 30 at r = 0.5 mm, 10.5 at 0.35 mm.
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// Applies the wall adhesion of every phase with a contact angle over the step dt, the colliders
/// placed at `time`. Call inside an OpenMP parallel region (an orphaned `omp for`).
void apply_fluid_wall_adhesion(const Model& model, FluidState& fluid, Real dt, Real time);

}  // namespace moreau
