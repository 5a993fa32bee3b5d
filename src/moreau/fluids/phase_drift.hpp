#pragma once
// Sub-particle drift of immiscible liquids (settings.fluid.phase_drift).
//
// The density constraint holds a settled liquid's particles in place as a packing of frictionless
// grains: a particle passes its neighbours only by pushing them apart against the pressure, so a
// drop of one or two particles of a slightly lighter liquid (oil in water) stays where it is,
// where a real drop of that size rises at its terminal speed. The drift restores that motion at
// the scale the particles cannot resolve: a particle of one liquid that is dispersed in another
// (fewer than half of its kernel-weighted neighbourhood, itself included, is its own liquid)
// trades places with a neighbour of the other liquid across gravity, the lighter going up, at the
// rate at which a drop of one particle's volume would rise or sink through the surrounding liquid.
//
// A trade exchanges two particles' positions and nothing else: each keeps its mass, velocity,
// temperature and identity, so the momentum, each liquid's mass and the density constraints
// (which read positions only) are unchanged; the weight's potential energy falls by
// (m_heavy - m_light) |g| s, s the height the two swap across, as a drop's drag would dissipate it.
//
// Rate: a drop of volume V = (2 r)^3 (diameter d = (6 V / pi)^(1/3)) in a liquid of density rho_c
// and viscosity mu_c reaches the terminal speed u where its buoyant weight meets its drag,
//   |rho_d - rho_c| g V = C_d(Re) rho_c u^2 pi d^2 / 8,   Re = rho_c u d / mu_c,
// with the Schiller & Naumann (1933) drag coefficient C_d = 24/Re (1 + 0.15 Re^0.687) for
// Re < 1000 and 0.44 above. A pair s apart across gravity trades with probability u dt / s per
// step, so a dispersed particle climbs at u on average. The draw hashes the step and the two
// particles' ids, so runs are reproducible and independent of the thread count.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct FluidModel;
struct FluidState;
struct Model;

/// Terminal speed (m/s) of a sphere of diameter d (m) and density rho_drop in a liquid of density
/// rho_liquid and dynamic viscosity mu (Pa s; 0: the Newton drag regime), under gravity g (m/s^2).
Real terminal_drift_speed(Real d, Real rho_drop, Real rho_liquid, Real mu, Real g);

/// Fills fm.drift_speed (phase a dispersed in phase b at [a * phases + b]) for gravity g.
void set_up_phase_drift(FluidModel& fm, Real g);

/// One step's trades (call at the start of a step, outside a parallel region, with the neighbour
/// lists of the previous step) on up to `threads` threads. The step's start time seeds the draw.
/// Returns the number of trades; marks the lists stale when there were some.
Index drift_phases(const Model& model, FluidState& fluid, Real time, int threads);

}  // namespace moreau
