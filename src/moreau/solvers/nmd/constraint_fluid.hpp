#pragma once
// Constraint fluids (Bodin, Lacoursiere, Servin 2012, "Constraint Fluids", IEEE TVCG 18(3)): the
// particle fluid at the velocity level, one SPOOK row per fluid particle in the same system as
// every body, cloth and soft body, so the coupling is two-way by construction.
//
// Density row of particle i (the volume form of fluids/density_constraint.hpp):
//   C_i = V sum_j W(x_i - x_j) + sum_b V_b W(x_i - x_b) + sum_s V_s W(x_i - x_s) - 1
// over fluid neighbours j (i included), collider wall samples b and solid samples s, with the
// Jacobian grad_{x_i} C_i on v_i, -V grad W_ij on each neighbour v_j, and through each solid
// sample x_s = x_body + R s (or sum_k b_k x_k) its body's linear and angular velocity
// (g, (x_s - x_body) x g) or its particles' (b_k g), g = -V_s grad W(x_i - x_s).
// The row pushes only (the fluid has no tension): its force multiplier lambda = l / h <= 0, and
// -lambda / V is the particle's pressure. Its compliance eps = 1 / (K V) makes the fluid as
// compressible as a bulk modulus K (C = eps lambda = p / K); SPOOK stays stable as K grows.
// Walls are unilateral rows too: a particle keeps distance r from every collider surface
// (speculative contacts, frictionless), and distance 1.5 r from every solid sample, the closest
// approach the position-level fluid keeps (solid_coupling.hpp).
#include <array>
#include <vector>

#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/solvers/nmd/nmd_system.hpp"

namespace moreau {

struct Model;
struct State;

/// The fluid's rows of one NMD solve: emitting, placing the samples and the neighbour lists
/// before the velocities are gathered; the rows; the pressure and the velocity passes after.
class ConstraintFluid {
 public:
  /// Once per step, before the first solve: releases the emitters' particles due at `time`.
  void start_step(const Model& model, State& state, Real time, int threads);
  /// Before each solve (and before VelocitySpace::gather: a rebuild re-sorts the particles):
  /// places the wall and solid samples at `time` and updates the neighbour lists.
  void prepare(const Model& model, State& state, Real time, int threads);
  /// Adds every particle's density row and its wall and solid-sample contacts for a solve of
  /// length h ending at `end_time`; records each particle's density.
  void add_rows(const Model& model, State& state, const VelocitySpace& space, Real h, Real end_time,
                NmdBlockInput& input, NmdSystem& system);
  /// After store_impulses: each particle's pressure from its row's impulse.
  void store_pressure(const Model& model, State& state, Real h);
  /// x += h v for the fluid particles, then the hard guarantee of fluid_motion.hpp: every particle
  /// at least r clear of every collider placed at `time`.
  void integrate(const Model& model, State& state, Real h, Real time);
  /// Once per step, after the last solve: viscosity, XSPH, vorticity confinement, surface tension,
  /// the walls' adhesion and interfacial tension over dt (fluid_velocity.hpp, surface_tension.hpp,
  /// wall_adhesion.hpp, interfacial_tension.hpp) and the CFL monitor.
  void finish_step(const Model& model, State& state, Real dt, Real h, int threads);

 private:
  void add_density_row(const Model& model, State& state, const VelocitySpace& space, Index i, NmdBlockInput& input,
                       NmdSystem& system, Real h);

  FluidScratch scratch_;
  std::vector<Real> multiplier_;  // per particle: lambda h^2 (kg m^2), the rows' warm start
  // The density row being built: its ends and their six Jacobian entries each.
  std::vector<VelocityEnd> row_end_;
  std::vector<std::array<Real, 6>> row_jacobian_;
};

}  // namespace moreau
