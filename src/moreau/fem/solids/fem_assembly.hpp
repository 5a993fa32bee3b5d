#pragma once
// Global assembly of the FEM engine. Cells are computed in parallel, one colour at a time (no two
// cells of a colour share a node), and scattered straight into the global arrays, so every
// global entry receives its cells' contributions in colour order whatever the thread count:
// results are bit-identical on any number of threads.
#include "moreau/fem/solids/fem_model.hpp"

namespace moreau {

struct InternalForceResult {
  Real energy = 0;                 // stored energy, J (2D: J per metre of thickness)
  bool valid = true;               // false: a cell's W is undefined (inverted)
  std::string invalid_solid;       // where, when not valid
  Index invalid_cell = -1;
};

/// Internal forces f_int(u) on all dofs (reactions included at prescribed ones) and the stored
/// energy; if `tangent` is given, also K = d f_int / du on the free dofs (structure of model.pattern).
/// `threads`: worker threads (0 = all cores); the result does not depend on it.
InternalForceResult assemble_internal_forces(const FemModel& model, const VectorX& u, VectorX& force,
                                             SparseMatrix* tangent, int threads = 0);

/// The algorithmic internal force of a time step from u_n to u_next (solid_element_step) on all
/// dofs, the stored energy at u_next, and (if `tangent` is given) d f / d u_next on the free dofs.
InternalForceResult assemble_step_forces(const FemModel& model, const VectorX& u_n, const VectorX& u_next,
                                         StepRule rule, VectorX& force, SparseMatrix* tangent, int threads = 0);

/// K(u) d on all dofs, with K the full tangent (prescribed rows and columns included).
VectorX tangent_times(const FemModel& model, const VectorX& u, const VectorX& direction);

/// The consistent mass matrix on the free dofs, with the structure of model.pattern (so that
/// its values add to a tangent's entry by entry).
SparseMatrix assemble_mass_matrix(const FemModel& model);

/// M x on all dofs (consistent mass).
VectorX mass_times(const FemModel& model, const VectorX& x);

/// External forces f_ext(t) on all dofs: the sum of the model's nodal loads.
VectorX external_forces(const FemModel& model, Real t);

/// Displacements of the prescribed dofs at time t written into u (the free ones untouched).
void apply_prescribed(const FemModel& model, Real t, VectorX& u);

/// Velocities of the prescribed dofs at time t written into v: the time derivative of their
/// values, by central differences (step 1e-6 s; exact for polynomials up to degree 2).
void apply_prescribed_velocity(const FemModel& model, Real t, VectorX& v);

/// The free components of a full-dof vector.
VectorX free_part(const FemModel& model, const VectorX& full);
/// Adds a free-dof vector into a full-dof vector.
void add_free_part(const FemModel& model, const VectorX& free, VectorX& full);

}  // namespace moreau
