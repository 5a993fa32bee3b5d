#pragma once
// A gas in open air (a fluid's "gas" entry): smoke or steam, whose particles move through air that
// the scene does not simulate (Macklin, Mueller, Chentanez & Kim 2014, "Unified particle physics
// for real-time applications", ACM TOG 33(4), section on gases).
//
// Weight: the air has the gas's rest density rho0 (at its reference temperature), so the air's
// pressure carries the weight m g of every particle, and only the Boussinesq part of gravity is
// left (fluid_heat.hpp, fluid_weight_factor):
//   dv/dt = -beta (T - T_ref) g,
// upward for warm gas (Fedkiw, Stam & Jensen 2001, "Visual simulation of smoke", whose buoyancy
// force has this form). A gas without an expansion is weightless and drifts with the air.
//
// Drag: where the gas's own neighbourhood is incomplete (its SPH density rho_i below rho0, at the
// edge of a plume or for a lone particle) the air fills the rest of it and drags the particle
// toward the wind v_air (Macklin et al. 2014):
//   dv/dt = -k (1 - rho_i / rho0) (v - v_air),
// with rho_i from the last density evaluation, the factor clamped to [0, 1]. It is integrated
// exactly over the step for a constant factor, v <- v_air + (v - v_air) exp(-k s dt), so no drag
// coefficient can overshoot. A lone particle (rho_i / rho0 = V W(0) = 1/pi for the cubic spline
// with h = 4 r) has s = 1 - 1/pi and reaches the terminal velocity
//   v = v_air - beta (T - T_ref) g / (k (1 - 1/pi)).
//
// Marker and mixing: each gas particle carries a smoke concentration c, 1 as it is released. Where
// the air reaches it, the air mixes in at the rate `mixing` (1/s), diluting the smoke and bringing
// the temperature to the air's T_ref alike:
//   dc/dt = -m s c,   d(H - H_ref)/dt = -m s (H - H_ref),
// with the same open fraction s and H_ref the specific enthalpy at T_ref (for a gas with an
// expansion, which gives T_ref; another gas keeps its heat). A plume therefore fades
// and cools from its edges, and loses its buoyancy as it entrains air.
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// Drags the particles of gas fluids toward their wind and mixes air into their smoke and heat over
/// the step dt. Call inside an OpenMP parallel region (every thread), after the step's last
/// density evaluation.
void apply_ambient_air(const Model& model, FluidState& fluid, Real dt);

}  // namespace moreau
