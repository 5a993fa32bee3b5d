#pragma once
// The implicit viscosity of the particle fluid and its friction at collider walls (settings.fluid.
// viscosity_solver "implicit", or "auto" where the viscosity is strong; the explicit one is
// Monaghan's Laplacian in fluid_velocity.hpp), every substep (apply_implicit_fluid_viscosity).
//
// The viscous force is the divergence of the Newtonian stress tau = 2 mu D, D = sym(grad v), with
// corrected kernel gradients (Bonet & Lok 1999, "Variational and momentum preservation aspects of
// SPH formulations", CMAME 180, sec. 3-4), so the velocity gradient is exact for linear fields on
// any neighbourhood (r_kj = x_k - x_j, grad W_kj = g_kj r_kj, V = (2r)^3, mu_k = rho0 nu_k with nu_k the
// particle's kinematic viscosity, its phase's or its state's, fluid_heat.hpp; next to another
// liquid, mu_k is the harmonic mean over the kernel, interface_viscosity.hpp):
//   M_k = -sum_j V g_kj r_kj r_kj^T,  L_k = M_k^-1     (eigenvalues of M_k floored at 0.2; 1 in a full
//                                                        neighbourhood, so spray droplets stay bounded)
//   G_k = sum_j V g_kj (v_j - v_k) r_kj^T L_k            (velocity gradient)
//   S_k = 2 mu_k sym(G_k) L_k                            (stress times the correction)
//   f_k = V^2 sum_j g_kj (S_j + S_k) r_kj                (force on particle k, N)
// f = -B^T (2 mu V sym(B v)) for the linear map B: v -> G: the force is the negative gradient of the
// dissipation sum_k V mu_k |sym G_k|^2, pairs are equal and opposite, and the pair torques cancel
// because tau_k L_k M_k = tau_k is symmetric. In Poiseuille flow it is exact in the interior where
// Monaghan's Laplacian on the same lattice gives 0.70 of the shear stress.
//
// The stress divergence spans two kernel radii and cannot see velocity modes that alternate from
// one particle to the next. A stabilising term damps them: Monaghan's compact Laplacian applied to
// each pair's departure from the corrected gradients,
//   e_kj = v_k - v_j - (G_k + G_j) r_kj / 2      (zero for any quadratic v: trapezoidal rule)
//   f_k += m_k 10 sum_j V mu_kj nu_kj g_kj (r_kj . e_kj) r_kj / (|r_kj|^2 + 0.01 h^2)
// with mu_kj = 2 m_j / (m_i + m_j) and nu_kj the pair's viscosity (the mean of the two within a
// phase, interface_viscosity.hpp). It leaves smooth
// flow unchanged, and as e_kj = -e_jk along r_kj it conserves linear and angular momentum.
//
// Walls: a wall sample b of collider c moves with the collider's velocity v_c and enters the sums
// of M_k and G_k with its volume V_b times the collider's `fluid_friction` f_c in [0, 1]: 0 leaves
// the wall free-slip (the sample is not in the sums), 1 is no-slip, between is a partial slip.
// - Velocity: no-slip follows Morris, Fox & Zhu (1997, "Modeling low Reynolds number
//   incompressible flows using SPH", J. Comput. Phys. 136, sec. 3.3). The sample takes the
//   velocity that extrapolates the particle's linearly through the wall surface,
//     v_b - v_k  ->  beta_kb (v_c - v_k),  beta_kb = 1 + d_b / max(d_k, r),
//   with d_k the particle's distance from the surface and d_b = r the sample's depth behind it
//   (boundary_sampling.hpp). A linear shear flow that vanishes at the wall then has the exact
//   gradient.
// - Traction: the wall's traction on particle k is V sum_b f_c V_b g_kb (S_b + S_k) r_kb. It uses
//   the stress extrapolated to the sample, S_b = S_k + grad S_k (x_b - x_k), with grad S_k the
//   corrected gradient over the fluid neighbours. Taking S_b = S_k, as the adjoint of the wall
//   terms of G would, gives half the wall shear stress of Poiseuille flow.
// - Rigid bodies with `fluid_friction` f are walls of the same kind: their surface samples
//   (solid_sampling.hpp, r behind each face) enter the sums with weight f V_s, move with the body,
//   and extrapolate as above with d_k the particle's distance from the body's shape and v_c the
//   body's velocity v_b + w_b x (x - x_b) at the point x where the segment from the particle to
//   the sample crosses the surface (so liquid turning with the body has no shear). The body takes
//   the opposite of their traction (apply_implicit_fluid_viscosity).
// - Cloth, soft bodies and continua with `fluid_friction` f are walls too: their samples (on a
//   sheet's mid-surface; r inside a soft body's boundary faces; a continuum's particles) move with
//   their particles,
//   u_s = sum_i b_i v_i, and are not extrapolated (beta = 1). The particles take the opposite of
//   the samples' traction, split by the barycentric weights.
//
// Time stepping: backward Euler over dt (the substep under XPBD, the step under nmd), from the
// velocity v* after the position solve (m_k = rho0 V):
//   (M + dt K) dv = dt f(v*),   K u = -f(u) with the wall velocities zero.
// The extrapolated wall stress makes K slightly unsymmetric. The system is solved by
// right-preconditioned BiCGSTAB (van der Vorst 1992) from dv = 0, to a relative residual
// |r| / |b| <= tolerance. The preconditioner is the particles' 3 x 3 diagonal blocks,
//   m_k I + dt sum_i V mu_i (|c_ik|^2 I + c_ik c_ik^T) - dt (the stabilising term's block),
// where c_ik is dG_i/dv_k as a vector. Weiler, Koschier, Brand & Bender (2018, "A physically
// consistent implicit viscosity solver for SPH fluids", CGF 37(2)) solve a system of this kind
// with CG. Dot products are summed over fixed blocks of particles in a fixed order, so the result
// does not depend on the thread count.
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;
struct State;

/// Solves the implicit viscosity over h and adds the change to the velocities, if the model's
/// viscosity is implicit and some phase has one; counts the solver's work in fluid.viscosity_stats. Call inside an OpenMP parallel region (every
/// thread): the XPBD formulations call it every substep after the velocity update (once per step
/// of 10 substeps let a very viscous fluid between no-slip walls go unstable together with the
/// density solve, docs/validation.md), the velocity-level one once per step.
/// Rigid bodies, cloth, soft bodies and continua with `fluid_friction` grip the fluid at their surface samples
/// as the collider walls do, each sample moving with its solid, and take the opposite of the
/// viscous force they exert (apply_rough_solid_reactions): `state` gives their motion and
/// receives the reaction (the rigid bodies' velocities, the particles' velocities).
void apply_implicit_fluid_viscosity(const Model& model, State& state, FluidScratch& scratch, Real h);

/// True if any phase has a viscosity.
bool fluid_has_viscosity(const Model& model);

}  // namespace moreau
