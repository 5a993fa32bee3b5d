#pragma once
// What the scene fixes about the fluids: their phases (one per fluid object), the particles they
// start with, the sampled collider walls, the sampled cloth and soft-body surfaces and the solver
// constants.
//
// All fluid particles share one radius r (lattice spacing 2 r, rest volume V = (2 r)^3) and one
// kernel support h = 4 r; phases differ in rest density (mass m = rho0 V), viscosity and
// vorticity confinement. Fluid particles live in their own arrays (FluidState), which are
// re-sorted along a z-order curve whenever the neighbour lists are rebuilt.
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "moreau/fluids/fluid_emitter.hpp"
#include "moreau/fluids/sph_kernel.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

struct FluidPhase {
  Index object = -1;               // scene object
  Real rest_density = 1000;        // rho0, kg/m^3
  Real particle_mass = 0;          // kg, rho0 V
  Real xsph = 0;                   // XSPH velocity smoothing c, applied once per step (dimensionless)
  Real viscosity = 0;              // kinematic viscosity nu, m^2/s
  Real surface_tension = 0;        // gamma against air, N/m (surface_tension.hpp)
  Real wall_adhesion = 0;          // W_a = gamma (1 + cos theta) on the colliders, N/m (wall_adhesion.hpp)
  Real vorticity = 0;              // vorticity-confinement strength epsilon, m/s (see fluid_velocity.hpp)
  Real relaxation = 0;             // epsilon of the density constraint, 1/(kg m^2) (scaled, see density_constraint.hpp)
  Real compliance = 0;             // eps of the density row under "nmd", 1/J: 1 / (K V) (solvers/nmd/constraint_fluid.hpp)
  // Heat (fluid_heat.hpp). A phase without conductivity neither gains nor loses heat.
  Real temperature = 293.15;       // K, of the initial and emitted particles
  Real conductivity = 0;           // k, W/(m K)
  Real specific_heat = 4186;       // c, J/(kg K), the same in both states
  std::optional<Real> melting_point;  // T_m, K; none: liquid at every temperature
  Real latent_heat = 0;            // L, J/kg
  Real solid_viscosity = 0;        // m^2/s, kinematic, of a particle that begins to melt (fluid_heat.hpp)
  // Buoyancy (Boussinesq, fluid_heat.hpp): the weight of a particle at T is m g (1 - beta (T - T_ref)).
  Real expansion = 0;              // beta, volumetric thermal expansion coefficient, 1/K (0: no buoyancy)
  Real reference_temperature = 0;  // T_ref, K, at which the phase has its rest density
  // A gas in open air (ambient_air.hpp): weightless but for its buoyancy, dragged toward the wind.
  bool gas = false;
  Real gas_drag = 0;               // k, 1/s
  Real gas_mixing = 0;             // m, 1/s: the air dilutes the smoke (and a buoyant gas's heat)
  Vec3 wind = Vec3::Zero();        // m/s
};

/// An interface between two liquids with a tension of its own (interfacial_tension.hpp).
struct FluidInterface {
  Index phase_a = -1, phase_b = -1;
  Real tension = 0;  // sigma, N/m
};

/// The largest kinematic viscosity (m^2/s) a particle of the phase can have: the liquid's, or, with
/// a melting point, the solid's if that is larger.
inline Real largest_viscosity(const FluidPhase& phase) {
  return phase.melting_point ? std::max(phase.viscosity, phase.solid_viscosity) : phase.viscosity;
}

/// Collider walls sampled with particles (Akinci et al. 2012): each sample carries the volume
/// V_b = 1 / sum_k W(x_b - x_k) over the samples k of its neighbourhood, so a wall contributes
/// the density of the fluid it replaces and the fluid next to it is not particle-deficient.
struct FluidBoundarySamples {
  std::vector<Vec3> local_position;  // m, offset from the collider position (world axes; colliders do not rotate)
  std::vector<Real> volume;          // m^3
  std::vector<Index> collider;       // index into Model::colliders
  bool moving = false;               // some sample belongs to a kinematic collider

  Index size() const { return static_cast<Index>(volume.size()); }
};

/// Cloth, soft-body and rigid-body surfaces sampled for the fluid (two-way coupling,
/// solid_coupling.hpp). A cloth or soft-body sample is a fixed barycentric combination of up to
/// four particles of the model (a cloth triangle, or the soft-body tetrahedron that holds a point r
/// inside the surface); a rigid-body sample is a fixed point of its body's frame. Either way it
/// moves with the solid and passes the fluid's push back to it.
struct FluidSolidSamples {
  std::vector<std::array<Index, 4>> particle;  // model particle indices (unused slots, rigid samples: weight 0)
  std::vector<std::array<Real, 4>> weight;     // barycentric weights, summing to 1 (all 0 for rigid samples)
  std::vector<Real> volume;                    // m^3, Akinci volume (boundary_sampling.hpp)
  std::vector<Index> object;                   // owning scene object
  // Rigid-body samples: the body (-1 for cloth and soft-body samples), the body-frame point, and
  // the body's generalised inverse mass bound there, 1/m + |r|^2 max(I^-1) (0 unless dynamic).
  std::vector<Index> body;
  std::vector<Vec3> body_point;                // m
  std::vector<Real> body_weight;               // 1/kg
  // The particle fluids' wall friction at the sample, in [0, 1] (fluid_viscosity.hpp): its object's
  // `fluid_friction` (cloth, soft bodies, rigid bodies, continua).
  std::vector<Real> friction;
  bool any_friction = false;                   // some sample has friction
  bool any_particle_friction = false;          // some cloth, soft-body or continuum sample has friction
  // The bodies with samples and their contiguous sample ranges [body_begin[j], body_begin[j+1]).
  std::vector<Index> sampled_body;
  std::vector<Index> body_begin;
  // Particle -> samples (CSR over `coupled_particle`), so each particle gathers its reaction.
  std::vector<Index> coupled_particle;         // model particles touched by some sample
  std::vector<Index> coupled_begin;            // coupled_particle.size() + 1 offsets
  std::vector<Index> coupled_sample;
  std::vector<Real> coupled_weight;

  Index size() const { return static_cast<Index>(volume.size()); }
};

/// How the viscosity is integrated (fluid_velocity.hpp, fluid_viscosity.hpp). The scene builder
/// resolves `automatic` to implicit where nu dt / h^2 > 0.01 or a wall has fluid friction, and to
/// explicit otherwise.
enum class ViscositySolver { automatic, explicit_update, implicit_solve };

struct FluidModel {
  Real particle_radius = 0;        // r, m
  Real particle_volume = 0;        // V = (2 r)^3, m^3
  CubicSplineKernel kernel;        // support h = 4 r
  Real neighbor_skin_fraction = 0;    // skin / h (settings.fluid.neighbor_skin); 0: lists per substep, as PBF
  Real neighbor_skin = 0;          // m: lists hold pairs closer than h + skin; rebuilt when a particle moved skin/2
  Real tensile_k = 0.1;            // s_corr = -k (W(r)/W(dq h))^4 (Macklin & Mueller 2013, sec. 4)
  Real tensile_inv_w_dq = 1;       // 1 / W(dq h) with dq = 0.2, m^3
  Real tensile_reference = 0;      // g_ref h, m^2/s^2: s_corr's pressure scale per unit mass
  Real solid_contact_distance = 0;  // m, 1.5 r: closest approach of a fluid particle to a solid sample
  Real cfl_limit = 0.4;            // warn when max |v| h / (2 r) exceeds it (Bender's PBD uses 0.4)
  ViscositySolver viscosity_solver = ViscositySolver::automatic;
  Real viscosity_tolerance = 1e-4;   // implicit: |r| / |b| to stop at
  int viscosity_max_iterations = 200;  // implicit: BiCGSTAB iterations at most per solve
  bool thermal = false;            // some fluid carries heat (fluid_heat.hpp)
  bool buoyant = false;            // some fluid's weight is not m g (an expansion, or a gas in open air)
  bool gas = false;                // some fluid is a gas in open air (ambient_air.hpp)
  Real heat_step_limit = 0;        // s, the longest stable explicit part of the heat update
  bool phase_drift = false;        // a lighter liquid's particles under a heavier one's trade places with them (phase_drift.hpp)
  std::vector<Real> drift_speed;   // m/s, terminal speed of one particle of phase a in phase b at [a * phases + b]

  std::vector<FluidPhase> phases;
  std::vector<FluidInterface> interfaces;  // pairs of liquids whose interface has a tension
  // Initial particles.
  std::vector<Vec3> initial_position, initial_velocity;  // m, m/s
  std::vector<Index> initial_phase;
  Index capacity = 0;              // particles the state reserves (initial + emitted)
  std::vector<FluidEmitter> emitters;

  FluidBoundarySamples boundary;
  FluidSolidSamples solid;

  bool empty() const { return phases.empty(); }
  Index initial_count() const { return static_cast<Index>(initial_position.size()); }
  Real support() const { return kernel.h; }
};

}  // namespace moreau
