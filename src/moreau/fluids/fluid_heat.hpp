#pragma once
// Heat in the particle fluids: a temperature per particle, conduction between particles and from
// collider walls held at a temperature, and melting and freezing through the enthalpy method.
//
// Solid state: a particle whose liquid fraction is 0 is fixed where it is (inverse mass 0, at rest;
// set_fluid_particle_state). The liquid flows around it and rests on it as on a wall: it counts in
// its neighbours' density, and its own density constraint keeps the multiplier it would have as a
// liquid, which only its liquid neighbours act on (project_fluid_density.cpp). Without that
// multiplier the liquid crowded into a crust freezing under its weight, 16 % over the rest density.
// A particle that freezes stops where it froze; one that melts moves again.
//
// State: each particle carries its specific enthalpy H (J/kg). With the phase's specific heat c,
// melting point T_m and latent heat L (the enthalpy method of the Stefan problem, Shamsundar &
// Sparrow 1975, with one c for both states):
//   H <  c T_m          solid,    T = H / c,          liquid fraction phi = 0
//   c T_m <= H <= c T_m + L       T = T_m,            phi = (H - c T_m) / L   (melting)
//   H >  c T_m + L      liquid,   T = (H - L) / c,    phi = 1
// A phase without a melting point is liquid at every temperature, T = H / c. The kinematic
// viscosity interpolates geometrically, nu = nu_solid^(1 - phi) nu_liquid^phi.
//
// Conduction: rho c dT/dt = div(k grad T), the SPH Laplacian of Brookshaw (1985) with the pair
// conductivity of Cleary & Monaghan (1999, "Conduction modelling using SPH", J. Comput. Phys. 148),
// for particles of equal volume V (r = x_i - x_j, grad W = g r, g < 0, eta^2 = 0.01 h^2):
//   m_i dH_i/dt = V sum_j V 2 k_ij (T_i - T_j) g_ij |r|^2 / (|r|^2 + eta^2),
//   k_ij = 2 k_i k_j / (k_i + k_j)          (harmonic mean: no heat crosses into an insulator).
// For T smooth, sum_j V 2 g (T_i - T_j) = H_T : M with M = -sum_j V g r r^T, the moment of the
// kernel gradient: on the particle lattice (h = 4r) M = 0.992 I with the eta term, so the Laplacian
// is 0.8 % low there. Each pair moves as much heat into one particle as out of the other, so
// between insulated walls the fluids' total enthalpy is constant to round-off.
//
// Walls: a collider with a `temperature` T_c holds its surface at T_c. Its wall samples (one layer,
// r behind the surface, boundary_sampling.hpp) take the temperature that extrapolates the
// particle's linearly through the surface, as the no-slip velocity does (wall_extrapolation.hpp):
//   T_i - T_b -> beta (T_i - T_c),  beta = 1 + r / max(d_i, r),
// with d_i the particle's distance from the surface, and enter the sum with their volume V_b and
// the particle's conductivity. On the lattice this is the second-order finite-difference
// Dirichlet condition at the surface. Colliders without a temperature are insulating.
//
// Buoyancy (the Boussinesq approximation; Boussinesq 1903, as in Gray & Giorgini 1976, "The
// validity of the Boussinesq approximation for liquids and gases", Int. J. Heat Mass Transfer 19):
// the density varies with temperature only in the weight,
//   rho0 Dv/Dt = -grad p + rho0 (1 - beta (T - T_ref)) g,
// with beta the volumetric expansion coefficient and T_ref the temperature at which the phase has
// its rest density rho0. The density constraint keeps every particle at rho0 (the flow stays
// incompressible); only gravity is scaled per particle. Valid while beta |T - T_ref| << 1: for an
// ideal gas beta = 1 / T_ref, so a plume 30 K hotter than air at 300 K is within 10 %.
//
// Time stepping: explicit (forward Euler, Jacobi), once per step after the velocity corrections,
// in as many equal parts as stability asks. By Gershgorin's theorem the update matrix's
// eigenvalues are at most twice the largest row sum max_i sum_j V 2 k_ij |g| r^2 / (r^2 + eta^2) /
// (rho_i c_i). With S = sum_j 2 V |g| r^2 / (r^2 + eta^2) = 17.1 / h^2 on the lattice and k_ij <= 2 k_i
// (the harmonic mean is at most twice the smaller conductivity; beta <= 2 keeps the wall rows
// within the same bound), that is 4 alpha_max S, and forward Euler needs tau <= 2 / (4 alpha_max S).
// A part is tau <= 0.25 h^2 / (17.1 alpha_max): stable with a factor 2 to spare for compressed
// neighbourhoods. Water at r = 1 mm needs a part per 1.6 s: one a step in practice.
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;

/// The temperature (K) of a particle of `phase` with specific enthalpy H (J/kg).
Real fluid_temperature(const FluidPhase& phase, Real enthalpy);

/// Its liquid fraction in [0, 1] (1 for a phase without a melting point).
Real fluid_liquid_fraction(const FluidPhase& phase, Real enthalpy);

/// The specific enthalpy (J/kg) of a particle of `phase` at temperature T: solid at or below the
/// melting point, liquid above it.
Real fluid_enthalpy(const FluidPhase& phase, Real temperature);

/// The factor 1 - beta (T - T_ref) that scales gravity on a particle of `phase` with specific
/// enthalpy H (1 for a phase without an expansion coefficient); for a gas in open air, whose weight
/// the air carries (ambient_air.hpp), -beta (T - T_ref).
Real fluid_weight_factor(const FluidPhase& phase, Real enthalpy);

/// The kinematic viscosity (m^2/s) of a particle of `phase` with specific enthalpy H.
Real fluid_particle_viscosity(const FluidPhase& phase, Real enthalpy);

/// Sets particle i's viscosity from its enthalpy, and makes it immovable (inverse mass 0, at rest)
/// while it is solid or movable (1 / m) once it melts. A particle held in its emitter's nozzle
/// (FluidState::release_time > 0) keeps inverse mass 0 and its velocity, solid or not.
void set_fluid_particle_state(const FluidPhase& phase, FluidState& fluid, Index i);

/// The longest explicit part of a step (s) that conduction with these phases is stable for
/// (infinity without conduction).
Real fluid_heat_step_limit(const FluidModel& fluid);

/// Conducts heat over the step dt and updates each particle's viscosity from its enthalpy, if the
/// model's fluids are thermal. Call inside an OpenMP parallel region (every thread).
void apply_fluid_heat(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt);

}  // namespace moreau
