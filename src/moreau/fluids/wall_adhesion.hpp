#pragma once
// Wetting: a liquid's adhesion to the collider walls, set by its contact angle theta. Without it a
// wall meets the liquid as air does: the surface tension (surface_tension.hpp) rounds the liquid
// off against it, a contact angle of 180 degrees. Young's (1805) balance of the three tensions at
// the contact line, with Dupre's (1869) work of adhesion, gives the energy per wetted area that a
// wall of contact angle theta saves:
//   W_a = gamma (1 + cos theta)   (N/m; 0 at 180 degrees, 2 gamma, the liquid's own, at 0),
// and this stage gives it to the liquid as a potential in the distance z from each collider surface:
//   U(z) = -k W_a (2r)^2 psi(z),   psi(z) = c (1 - z / z_a)^2 for z < z_a = 5r, 0 beyond,
// (2r)^2 the wall area a lattice particle covers, k a calibration (below). The particles are kept
// z >= r from a wall, so a column of lattice layers over the wall, at z = r, 3r, has psi summing to
// c (0.64 + 0.16) = 1 with c = 1.25: the column's energy is -k W_a per area. The range reaches the
// second layer on purpose. A pull on the first layer only (as Akinci et al. 2013's adhesion to
// boundary particles would be here, with the samples r inside the wall and the kernel's support 4r)
// presses that layer against the wall, and nothing draws the liquid over the edge of the wetted
// patch: the contact line stays where it is. The force -dU/dz points into the wall,
//   F = -k W_a (2r)^2 2c (1 - z / z_a) / z_a  n     (n the wall's normal into the liquid),
// applied to the velocities once per step after the surface tension. Every wall in reach adds its
// own: two colliders at a corner, and the two or three walls of a box tank near its edges and
// corners. Only colliders with wall samples (`fluid_walls`) wet the liquid, as k was calibrated
// with them. The walls take no reaction.
//
// Calibration. With k = 1, drops settled at angles 12-40 degrees larger than theta (112 for 90, 132
// for 120, 100 for 60). Why is not established: most likely the particles' wall does not cost the
// liquid exactly gamma, as the air it stands for would, or the discrete contact line is held back
// where Young's balance lets it move. k = 1.7 is the factor that put a 1 cm drop's cap at 94.1,
// 57.2 and 119.0 degrees for 90, 60 and 120 at r = 0.5 mm, and at 89.6, 56.4 and 116.2 at
// r = 0.35 mm (tests/fluids/test_fluid_wetting.cpp; docs/validation.md). Near complete wetting it
// spreads too far: 17 degrees for 30 at r = 0.5 mm, 10.5 at 0.35 mm.
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// Applies the wall adhesion of every phase with a contact angle over the step dt, the colliders
/// placed at `time`. Call inside an OpenMP parallel region (an orphaned `omp for`).
void apply_fluid_wall_adhesion(const Model& model, FluidState& fluid, Real dt, Real time);

}  // namespace moreau
