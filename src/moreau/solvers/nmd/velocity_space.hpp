#pragma once
// The generalised velocities of the velocity-level formulation and their inverse mass.
//
// One flat vector v: three entries per particle (its velocity), then six per rigid body (the
// velocity of its centre of mass, then its world angular velocity), then three per live fluid
// particle, then, when the model has grains, three per particle for its spin (the angular
// velocity of a grain, a solid sphere; the entries of particles that do not turn stay unused).
// A row's end is an offset into v (`dof`) and a size (3 or 6). The inverse mass W is block
// diagonal: 1/m I for a particle, diag(1/m I, I^-1) for a body with I^-1 = R diag(I_principal^-1)
// R^T in the world at the start of the solve (Lacoursiere 2007 linearises the inertia over a
// step), 5/(2 m r^2) I for a grain's spin. Pinned particles, fixed and kinematic bodies, sleeping
// and unborn grains have W = 0: their velocities enter the rows but no impulse changes them.
#include <vector>

#include "moreau/constraints/body_rows.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

struct Model;
struct State;

/// One end of a row block in the velocity vector; dof < 0 is the world (no velocity).
struct VelocityEnd {
  Index dof = -1;
  int size = 0;       // 3 (particle, fluid particle or spin) or 6 (body)
  bool moves = true;  // false when its inverse mass is zero (set by NmdSystem::add): impulses leave it alone

  bool is_world() const { return dof < 0; }
};

struct VelocitySpace {
  Index particles = 0, bodies = 0, fluids = 0;
  Index spins = 0;                     // particles when the model has grains (they turn), else 0
  std::vector<Real> v;                 // m/s and rad/s
  std::vector<Real> particle_inv_mass; // 1/kg
  std::vector<Real> fluid_inv_mass;    // 1/kg
  std::vector<Real> spin_inv_inertia;  // 1/(kg m^2) per particle when spins > 0: a moving grain's, else 0
  std::vector<Real> body_inv_mass;     // 1/kg
  std::vector<Mat3> body_inv_inertia;  // 1/(kg m^2), world

  Index particle_dof(Index p) const { return 3 * p; }
  Index body_dof(Index b) const { return 3 * particles + 6 * b; }
  Index fluid_dof(Index i) const { return 3 * particles + 6 * bodies + 3 * i; }
  Index spin_dof(Index p) const { return 3 * particles + 6 * bodies + 3 * fluids + 3 * p; }
  VelocityEnd end(const BodyEnd& e) const {
    switch (e.kind) {
      case BodyEndKind::world: return {};
      case BodyEndKind::body: return {body_dof(e.index), 6};
      case BodyEndKind::particle: return {particle_dof(e.index), 3};
    }
    return {};
  }
  VelocityEnd particle_end(Index p) const { return {particle_dof(p), 3}; }
  VelocityEnd fluid_end(Index i) const { return {fluid_dof(i), 3}; }
  /// Particle p's spin: its Jacobian entries are the three angular ones, in the first three slots.
  VelocityEnd spin_end(Index p) const { return {spin_dof(p), 3}; }
  /// Whether particle p turns in this solve (a grain that is awake and released).
  bool turns(Index p) const { return spins > 0 && spin_inv_inertia[p] > 0; }

  /// Whether an impulse can change the end's velocity (a non-zero inverse mass or inertia).
  bool moves(const VelocityEnd& e) const;

  /// The scalar inverse mass (or a spin's inverse inertia) of an end of size 3.
  Real point_inverse_mass(Index dof) const {
    if (dof < 3 * particles) return particle_inv_mass[dof / 3];
    if (dof < spin_dof(0)) return fluid_inv_mass[(dof - fluid_dof(0)) / 3];
    return spin_inv_inertia[(dof - spin_dof(0)) / 3];
  }
  /// W_e J^T for the 6 entries of one row's end (the angular half unused for particles).
  void apply_inverse_mass(const VelocityEnd& e, const Real* jacobian, Real* out) const;

  /// Reads the velocities and the inverse masses from the model and state (the body inertia at
  /// the current orientations).
  void gather(const Model& model, const State& state);
  /// v += h (g + gyroscopic acceleration) for every free particle, fluid particle and dynamic body: the
  /// unconstrained velocity v* = v + h M^-1 f. The gyroscopic term -w x (I w) is explicit; a
  /// grain's spin, a sphere's, has none.
  void apply_forces(const Model& model, const State& state, Real h);
  /// Writes the velocities back to the state (free particles, grains' spins, fluid particles and
  /// dynamic bodies).
  void scatter(const Model& model, State& state) const;
};

}  // namespace moreau
