#pragma once
// The fluid particles' part of the XPBD substep (Mueller et al. 2020, Algorithm 2, as for every
// particle): predict, apply the density corrections and keep particles out of colliders, derive
// velocities. Each function is an orphaned `omp for` over the live particles; call inside the
// step's parallel region.
//
// Colliders: a particle is kept at distance >= r (its radius) from every collider surface,
// including the inside walls of a tank (`"inside": true`). This position clamp is the hard
// guarantee against leaks; the wall samples in the density constraint are what make the fluid
// next to a wall have the right density (no sticking, no gap).
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// x_start = x; v += h g; x += h v. Also clears the substep's pressure sum. Particles of inverse
/// mass 0 are kinematic: they feel no weight and move on at their velocity, zero for a solid one
/// (fluid_heat.hpp), the emitter's for one held in its nozzle (fluid_emitter.hpp).
void predict_fluid(const Model& model, FluidState& fluid, FluidScratch& scratch, Real h);

/// x += dx of the last density iteration, accumulates the pressure p = -lambda / (V h^2), and
/// pushes particles out of colliders placed at `time` (not kinematic ones: they stay on their
/// course).
void apply_fluid_corrections(const Model& model, FluidState& fluid, const FluidScratch& scratch, Real h, Real time);

/// v = (x - x_start) / h, except for kinematic particles (inverse mass 0), which keep theirs.
void update_fluid_velocity(FluidState& fluid, const FluidScratch& scratch, Real h);

/// The CFL number max|v| h / (2 r) of this substep length h; records it in the state. Serial.
Real fluid_cfl_number(const Model& model, FluidState& fluid, Real h);

}  // namespace moreau
