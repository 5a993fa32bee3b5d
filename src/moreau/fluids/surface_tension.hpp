#pragma once
// Surface tension in N/m: the cohesion and curvature forces of Akinci, Akinci & Teschner 2013
// ("Versatile surface tension and adhesion for SPH fluids", ACM TOG 32(6)), written with the
// surface tension gamma (N/m) against air and calibrated so that a drop's shape oscillates at
// Rayleigh's frequency. Applied to the velocities once per step, like viscosity (sums over the
// liquid neighbours j within h, of any liquid, r = x_i - x_j, V the particle volume):
//   surface normal   n_i = h V sum_j grad W(r)                 (dimensionless, ~0 inside the fluid)
//   cohesion         F_ij = -a_coh gamma (V^2 / h^2) C(|r|) r / |r|
//   curvature        F_ij = -a_curv gamma h (n_i - n_j)
//   symmetrisation   K_ij = 2 rho0 / (rho_i + rho_j)           (stronger where the fluid is sparse;
//                    2 / (rho_i / rho0_i + rho_j / rho0_j) for a pair of two liquids)
//   v_i += dt / m_i sum_j K_ij (F_cohesion + F_curvature)
// with Akinci's cohesion spline (support h; repelling below 0.27 h, attracting beyond, strongest at h/2)
//   C(r) = 32 / (pi h^9) * { (h - r)^3 r^3                 h/2 < r <= h
//                           { 2 (h - r)^3 r^3 - h^6 / 64   0 < r <= h/2.
// Both forces are gamma h times a function of r / h, so the model is the same at every particle
// size and density: a drop of R / (2 r) particle spacings behaves alike at any scale. (Akinci's
// paper uses one coefficient in units that differ between the two terms.)
//
// The two weights. The curvature term pulls the surface smooth and carries most of the tension;
// it acts only at the surface, which keeps the drop's oscillation lightly damped. The cohesion
// binds the surface particles to the liquid (without it they leave a drop within 0.1 s), but it
// also puts the liquid under a uniform tension that the density constraint must hold, and that
// damps: a drop held by cohesion alone oscillates with a damping ratio near 0.45; with these
// weights it is 0.05-0.15. Halving a_coh again lets particles escape (measured: 1 % of a drop).
// The weights, a_coh = 27.4 and a_curv = 0.0548 (surface_tension.cpp), were then scaled together
// until the l = 2 oscillation of a drop matched Rayleigh's omega^2 = 8 gamma / (rho0 R^3): measured
// within -2.2 % .. +3.3 % in frequency for gamma 0.03-0.15 N/m, R / (2r) 10-20 and r 0.25-0.5 mm
// (tests/fluids/test_fluid_surface_tension.cpp; docs/validation.md).
//
// It is explicit, so the step must resolve the fastest capillary wave on the particle scale:
// dt <= sqrt(rho0 (2r)^3 / (2 pi gamma)) (capillary_time_step; the scene reader enforces it). That is
// Brackbill et al.'s (1992) limit with the liquid's density where they take the mean of the two
// fluids' (here the air carries none), sqrt(2) longer than theirs. Measured: a 1 cm water drop at
// r = 0.5 mm is stable at 0.94 of that step and falls apart at 1.7 of it.
// The pair forces are equal and opposite (the curvature term uses the pair's common weight), so
// linear momentum is conserved. Sign: with grad W(r) = g(|r|) r, g < 0, the normal as written
// points into the fluid; with the opposite sign the curvature term is anti-diffusive and a blob
// blows apart. A pair of particles of two liquids takes the mean of their gammas: where two
// liquids meet, each particle's neighbourhood is full and the normals vanish, so these forces act
// where liquid meets air and leave the interface between liquids to its own tension
// (interfacial_tension.hpp). Gas particles take no part, and walls attract the liquid only where it
// has a contact angle (wall_adhesion.hpp). The fluid's `pressure` (the density multipliers')
// includes the cohesive tension the constraint holds: about 0.73 gamma / h more than the mechanical
// pressure inside the liquid.
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// The largest step (s) that resolves the capillary waves on the lattice spacing s (m) of a fluid
/// of rest density rho0 (kg/m^3) and surface tension gamma (N/m): sqrt(rho0 s^3 / (2 pi gamma)).
Real capillary_time_step(Real rest_density, Real spacing, Real surface_tension);

/// Applies surface tension over the step dt to every phase with gamma > 0. Call inside an OpenMP
/// parallel region (uses FluidScratch::correction as the normals and reorder_vec for the result).
void apply_fluid_surface_tension(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt);

}  // namespace moreau
