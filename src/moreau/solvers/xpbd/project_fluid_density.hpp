#pragma once
// XPBD's projection of the fluid density constraints (fluids/density_constraint.hpp): Position
// Based Fluids (Macklin & Mueller 2013), Jacobi iterations inside the XPBD substep loop.
//
// Multiplier (PBD form with constraint-force mixing epsilon; walls have w = 0):
//   lambda_i = -max(C_i, 0) / (w_i |grad_{x_i} C_i|^2 + sum_j w_j V^2 |grad W_ij|^2 + epsilon_i)
//   The clamp makes the constraint unilateral: a particle with missing neighbours (free surface)
//   is not pulled inwards, which would clump the surface.
// Correction (Jacobi over all density constraints touching i, plus the tensile term):
//   dx_i = w_i [ sum_j V (lambda_i + lambda_j + s_ij) grad W_ij + lambda_i sum_b V_b grad W_ib ]
// m_i dx_i is antisymmetric in (i, j) and parallel to x_i - x_j, so the fluid-fluid corrections
// conserve linear and angular momentum.
//
// Tensile term (PBF sec. 4, "artificial pressure"): s_ij = -k (W_ij / W(dq h))^4 (S_i + S_j)/2 h_sub^2
// with k = 0.1, dq = 0.2. PBF adds s_corr as a fixed position push per iteration, so its strength
// would grow with the number of substeps; here it is an artificial pressure
//   p_s = k (W_ij / W(dq h))^4 rho0 g_ref h,     g_ref = 9.81 m/s^2 (10 % of the hydrostatic
// pressure one kernel radius deep at k = 0.1), entering like a multiplier: lambda = -p V h_sub^2.
// S_i = rho0_i g_ref h V = m_i g_ref h (FluidModel::tensile_reference = g_ref h).
//
// Units: C is dimensionless, lambda in kg m^2, w = 1/m in 1/kg. epsilon_i is scaled by
// D_rest = (V^2 / m) sum_j |grad W_ij|^2, the denominator of a particle inside a rest lattice:
// epsilon_i = relaxation * D_rest, so `relaxation` (dimensionless) keeps its meaning at any
// particle size and density (PBF's epsilon is in demo units). The pressure of particle i is
// p_i = -lambda_i / (V h_sub^2) (Pa), summed over the substep's iterations.
#include "moreau/math/types.hpp"

namespace moreau {

struct Model;
struct FluidState;
struct FluidScratch;

/// Lays out the kernel-value cache the iterations share (FluidScratch::pair_offset) for the
/// current neighbour lists. Call inside the OpenMP parallel region, by every thread, whenever the
/// lists were rebuilt and at the start of every step.
void lay_out_pair_cache(const FluidState& fluid, FluidScratch& scratch);

/// One Jacobi iteration: every lambda_i, then every correction into FluidScratch::correction
/// (apply_fluid_corrections moves the particles). Call inside an
/// OpenMP parallel region (orphaned omp for loops with barriers).
void project_fluid_density(const Model& model, FluidState& fluid, FluidScratch& scratch, Real h);

}  // namespace moreau
