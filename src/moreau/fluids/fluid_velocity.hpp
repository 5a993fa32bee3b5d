#pragma once
// Velocity corrections of the fluid, once per step after the last substep's v = (x - x_start)/h
// (Macklin & Mueller 2013, Algorithm 1, lines 21-24). Sums run over fluid neighbours j within h;
// v_ij = v_i - v_j, r_ij = x_i - x_j, grad W_ij = grad W(r_ij).
//
// Physical viscosity, when settings.fluid.viscosity_solver makes it explicit (the implicit one is
// fluid_viscosity.hpp, applied by the formulation) (Monaghan 2005, "Smoothed particle hydrodynamics", eq. 6.27 form used for laminar flow;
// d = 3 dimensions, kinematic viscosity nu in m^2/s, applied over dt):
//   a_i = 2 (d + 2) nu sum_j V (v_ij . r_ij) / (|r_ij|^2 + 0.01 h^2) grad W_ij
//   This is the SPH estimate of nu laplacian(v); it conserves linear and angular momentum.
//   Explicit, so it needs dt <= 0.125 h^2 / nu (checked when the scene is loaded). On the particle
//   lattice (spacing 2r, h = 4r) this stencil gives 0.70 of the shear stress of flow along a lattice
//   axis and 1.43 times it along a face diagonal (its mean over directions is right): it is the
//   fast choice where the viscosity barely acts (water), not an accurate one.
// XSPH smoothing (Schechter & Bridson 2012; PBF eq. 17), c dimensionless, per step:
//   v_i += c sum_j V (v_j - v_i) W_ij
// Vorticity confinement (Fedkiw et al. 2001; PBF eqs. 15-16), epsilon in m/s:
//   omega_i = sum_j V v_ij x grad W_ij                    (SPH curl of v; = 2 Omega for a rigid spin)
//   eta_i   = sum_j V (|omega_j| - |omega_i|) grad W_ij   (SPH gradient of |omega|)
//   a_i     = epsilon (N x omega_i),  N = eta_i / |eta_i|
// Between particles of different mass, the viscosity and XSPH pair terms carry the factor
// mu_ij = 2 m_j / (m_i + m_j) (1 for equal masses), so m_i dv_i = -m_j dv_j: both conserve linear
// momentum in multi-fluid scenes too. Viscosity acts along x_ij and also conserves angular
// momentum; XSPH does not (it damps rigid rotation near a free surface). A pair of two different
// liquids takes the harmonic mean of their dynamic viscosities (interface_viscosity.hpp), a pair
// within one liquid the mean of the two particles' nu.
// All three read the velocities from before the pass (Jacobi), so the result is order-free.
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// Applies viscosity, XSPH and vorticity confinement over the step dt. Call inside an OpenMP
/// parallel region.
void apply_fluid_velocity_corrections(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt);

/// The SPH curl of the velocity at particle i (1/s).
Vec3 fluid_vorticity(const Model& model, const FluidState& fluid, Index i);

}  // namespace moreau
