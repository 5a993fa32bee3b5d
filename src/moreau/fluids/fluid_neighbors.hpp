#pragma once
// Neighbour lists of the fluid particles, built with a CellGrid of cell edge h + skin (h the
// kernel support) and reused by every iteration until some particle has moved more than skin/2
// since the build (a Verlet list: no pair closer than h can be missing before that).
//
// A rebuild (1) sorts the live particles along the grid's z-order curve and permutes every fluid
// array with that order, so the particles of one cell, and of nearby cells, are adjacent in memory;
// (2) places the collider wall samples and (re)builds their grid when they move; (3) writes, for
// each particle, its fluid neighbours, its wall-sample and its solid-sample neighbours into
// fixed-length rows, and for each cloth/soft-body sample its fluid particles (the reverse lists
// the reaction is gathered over). Solid samples move every substep, so a scene with coupled
// solids rebuilds every substep whatever the skin.
// Rows are owned by their particle, so the parallel fill does not depend on the thread count.
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// Rebuilds the lists if needed. Call inside an OpenMP parallel region (every thread), after the
/// substep's prediction, after place_solid_samples and, when walls move, after
/// place_boundary_samples for `time`.
/// Returns true if it rebuilt.
bool update_fluid_neighbors(const Model& model, FluidState& fluid, FluidScratch& scratch, Real time);

/// Places the wall samples of kinematic colliders at `time` (every thread; orphaned omp for).
void place_boundary_samples(const Model& model, FluidState& fluid, Real time);

}  // namespace moreau
