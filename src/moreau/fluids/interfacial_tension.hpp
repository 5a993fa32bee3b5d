#pragma once
// The tension sigma (N/m) of the interface between two liquids: the continuum surface force of
// Brackbill, Kothe & Zemach (1992), f = sigma kappa grad c per unit volume, in the SPH form of
// Morris (2000) with the curvature's renormalised divergence of Adami, Hu & Adams (2010, "A new
// surface-tension formulation for multi-phase SPH using a reproducing divergence approximation",
// JCP 229). Where liquid meets air the Akinci forces act instead (surface_tension.hpp): a free
// surface lacks the neighbours a colour gradient needs, while at a liquid-liquid interface both
// sides are full.
//
// For an interface between liquids A and B, each particle i of either takes its own liquid as the
// colour c = 1 and the other as c = 0 (V the particle volume, grad W_ij = grad_i W(x_i - x_j)):
//   colour gradient   g_i = sum_j V (c_j - c_i) grad W_ij = -V sum_{j other} grad W_ij
//                     (points into i's own liquid; ~0 away from the interface)
//   unit normal       n_i = g_i / |g_i| where |g_i| > 0.01 / h (Morris's threshold), else none
//   curvature         kappa_i = -div n = -d sum_j (n_j - n_i) . grad W_ij / sum_j |x_ij| |grad W_ij|
//                     over the neighbours j of either liquid that have a normal, n_j taken in i's
//                     colour (negated for the other liquid); d = 3. The denominator makes the
//                     divergence exact for a linear field however few neighbours the band has.
//   velocity          v_i += dt sigma kappa_i g_i / rho0_i
// Each side sees the colour jump from its own side: g points into A on A's side and into B on B's,
// and kappa changes sign with it, so both sides are pushed toward the centre of curvature and the
// force integrated across the band is sigma kappa n, the Young-Laplace jump. Only forces through
// the pressure balance it: its momentum sums to sigma times the integral of kappa n over the
// interface, zero for a closed one.
//
// Explicit, like the Akinci forces: dt <= sqrt(rho (2r)^3 / (2 pi sigma)) with rho the two
// liquids' mean density (Brackbill's limit; the scene reader enforces it).
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// Applies the interfacial tension of every FluidModel::interfaces entry over the step dt. Call
/// inside an OpenMP parallel region after apply_fluid_surface_tension (uses FluidScratch::correction
/// for the colour gradients, reorder_vec for the normals and reorder_real for the curvatures).
void apply_fluid_interfacial_tension(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt);

}  // namespace moreau
