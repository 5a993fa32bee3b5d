#pragma once
// Surface tension and cohesion of the fluid, after Akinci, Akinci & Teschner 2013 ("Versatile
// surface tension and adhesion for SPH fluids", ACM TOG 32(6)), applied to the velocities once
// per step like viscosity (sums over fluid neighbours j of the same phase within h, r = x_i - x_j):
//   surface normal   n_i = h V sum_j grad W(r)            (dimensionless, ~0 inside the fluid)
//   cohesion         F_ij = -gamma m_i m_j C(|r|) r / |r|
//   curvature        F_ij = -gamma (m_i + m_j) / 2 (n_i - n_j)
//   symmetrisation   K_ij = 2 rho0 / (rho_i + rho_j)   (stronger where the fluid is sparse: the surface)
//   v_i += dt / m_i sum_j K_ij (F_cohesion + F_curvature)
// with Akinci's cohesion spline (support h; attracting beyond h/2, repelling closer)
//   C(r) = 32 / (pi h^9) * { (h - r)^3 r^3                 h/2 < r <= h
//                           { 2 (h - r)^3 r^3 - h^6 / 64   0 < r <= h/2.
// gamma is the paper's coefficient in SI units, so values carry over from it (and from SPH codes
// that implement it); the paper's two terms carry different units (gamma in m^4/(kg s^2) for
// cohesion, m/s^2 for curvature), and gamma is not a surface tension in N/m. The curvature term
// uses the mean mass instead of m_i, so F_ji = -F_ij exactly and linear momentum is conserved in
// multi-fluid scenes too. Pairs of different phases do not attract (immiscible fluids).
// Sign: with grad W(r) = g(|r|) r, g < 0, the normal as written points into the fluid; with the
// opposite sign the curvature term is anti-diffusive and a blob blows apart (measured). At the
// scene lattice (h = 4r) cohesion dominates: per neighbour it is ~40x the curvature term.
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// Akinci's cohesion spline C(r) for support h, 1/m^3.
Real cohesion_spline(Real r, Real h);

/// Applies surface tension over the step dt to every phase with gamma > 0. Call inside an OpenMP
/// parallel region (uses FluidScratch::correction as the normals and reorder_vec for the result).
void apply_fluid_surface_tension(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt);

}  // namespace moreau
