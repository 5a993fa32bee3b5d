#pragma once
// Sub-particle drift of immiscible liquids (settings.fluid.phase_drift).
//
// The density constraint holds a settled liquid's particles in place as a packing of frictionless
// grains: a particle passes its neighbours only by pushing them apart against the pressure, so a
// drop of a few particles of a slightly lighter liquid (oil in water) stays where it is, and a film
// of it on the floor under the heavier one stays there (a wall's samples carry no multiplier, so a
// light particle at a wall lacks the lift of the liquid around it), where a real drop of that size
// rises at its terminal speed. The drift restores that slip at the scale the particles cannot
// resolve: wherever a particle of a lighter liquid has one of a heavier liquid above it (within
// 1.5 spacings, at least r/2 higher), the two trade places at the rate at which a drop of one
// particle's volume rises or sinks through the liquid around it: the liquid of which the lighter
// particle has fewer neighbours is the drop. A resolved drop of the lighter liquid sheds particles
// on its way up, as its upper surface trades with the liquid above it.
//
// A trade exchanges two particles' positions (and, for the nmd solver's warm start, the pressure
// that goes with a position) and nothing else: each keeps its mass, velocity, temperature and
// identity, so the momentum, each liquid's mass and the density constraints
// (which read positions only) are unchanged; the weight's potential energy falls by
// (m_heavy - m_light) |g| s, s the height the two swap across, as a drop's drag would dissipate it.
//
// Rate: a drop of volume V = (2 r)^3 (diameter d = (6 V / pi)^(1/3)) in a liquid of density rho_c
// and viscosity mu_c reaches the terminal speed u where its buoyant weight meets its drag,
//   |rho_d - rho_c| g V = C_d(Re) rho_c u^2 pi d^2 / 8,   Re = rho_c u d / mu_c,
// with the Schiller & Naumann (1933) drag coefficient C_d = 24/Re (1 + 0.15 Re^0.687) for
// Re < 1000 and 0.44 above. A pair s apart across gravity trades with probability u dt / s per
// step, so a particle surrounded by the other liquid climbs at u on average, as long as u dt / s
// stays below 1: a particle trades at most once a step, so where u dt exceeds the height of the
// pair (large density differences, long steps) the climb is capped at about s / dt. The draw
// hashes the step and the two particles' ids, so runs are reproducible and independent of the
// thread count. With three or more liquids, a particle that proposes a trade to a heavier one
// does not accept one from a lighter one in the same step.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct FluidModel;
struct FluidScratch;
struct FluidState;
struct Model;

/// Terminal speed (m/s) of a sphere of diameter d (m) and density rho_drop in a liquid of density
/// rho_liquid and dynamic viscosity mu (Pa s; 0: the Newton drag regime), under gravity g (m/s^2).
Real terminal_drift_speed(Real d, Real rho_drop, Real rho_liquid, Real mu, Real g);

/// Fills fm.drift_speed (phase a dispersed in phase b at [a * phases + b]) for gravity g.
void set_up_phase_drift(FluidModel& fm, Real g);

/// One step's trades on up to `threads` threads: call at the start of a step, before particles are
/// emitted, outside a parallel region, with the neighbour lists of the previous step (nothing
/// trades before the lists were first built). `step`, the count of completed steps, seeds the draw.
/// Returns the number of trades; marks the lists stale when there were some.
Index drift_phases(const Model& model, FluidState& fluid, FluidScratch& scratch, long step, int threads);

}  // namespace moreau
