#pragma once
// The flow's equations with a source (an immersed solid or rigid body: FlowSource) in them.
//
// The source adds its forces to the Galerkin residual, R_A += R_src,A. Its force density on the
// fluid, f_A = -R_src,A / V_A (V_A = integral of N_A, the node's lumped volume), also enters the
// SUPG/PSPG strong residual, r_s = rho (du/dt + u . grad u - b) + grad p - f_h: the stabilization
// is then consistent where a body holds the fluid. Without f_h, PSPG reads the holding force as a
// pressure-gradient error of size tau |f| / (rho h) in the continuity equation and lets the fluid
// pass through the body: released in a fluid at rest, a disc started with a third of the added
// mass of potential flow, whatever the mesh.
//
// f is taken as zero on prescribed dofs (their source force is a reaction). The Jacobian is then
//   dR/dv = J_cells + (I + P) J_src,   P = -S diag(1 / V),   S = dR_cells / df,
// with J_src = sparse part + U V^T: the low-rank part stays low-rank, U <- (I + P) U.
#include "moreau/fem/flow/navier_stokes.hpp"

namespace moreau {

/// The residual on all dofs at x and, if `J` is given, the Jacobian on the free dofs (its
/// low-rank part in `low_rank`, which must then be given too) of the flow with `source` in it.
/// `source_s` accumulates the wall time of the source's own terms.
void assemble_flow_with_source(const NavierStokesModel& model, const VectorX& x, const FlowTimeStep& step,
                               const FlowSource& source, const FlowAssembly& how, VectorX& R, SparseMatrix* J,
                               FlowLowRank* low_rank, double& source_s);

/// The residual on all dofs at x of the flow with a source whose residual (on all dofs, as
/// FlowSource::add gives it) is `source_R`: on prescribed dofs, the reactions that hold the fluid
/// and the source there.
void flow_residual_with_source(const NavierStokesModel& model, const VectorX& x, const FlowTimeStep& step,
                               const VectorX& source_R, VectorX& R);

}  // namespace moreau
