#pragma once
// Buffers the particle fluid's step rewrites every substep or iteration and nothing outside the
// step reads: a solver keeps them in its workspace, next to the FluidState. Per-particle arrays
// hold the fluid's capacity and move with the particles when the neighbour search re-sorts them
// (substep_start) or are rewritten before they are read (the rest).
#include <array>
#include <vector>

#include "moreau/math/pose.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

struct FluidModel;

struct FluidScratch {
  std::vector<Vec3> substep_start;      // m, positions at the start of the substep
  std::vector<Real> lambda;             // density multiplier of the current iteration, kg m^2
  std::vector<Vec3> correction;         // m, Jacobi correction of the current iteration; the velocity
                                        // passes reuse it (vorticity, surface normals)
  std::vector<Vec3> wall_gradient;      // 1/m, sum_b V_b grad W_ib over wall and solid samples
  std::vector<Vec3> reorder_vec;        // the re-sort's and the velocity passes' second buffers
  std::vector<Index> reorder_index;
  std::vector<Real> reorder_real;
  std::vector<Real> temperature;        // K, per particle, during the heat update (thermal models only)
  std::vector<Real> heat_change;        // J/kg, per particle, of one part of the heat update
  // Coupling with cloth, soft bodies and rigid bodies (solid_coupling.hpp).
  std::vector<Vec3> solid_reaction;     // kg m, per solid sample: -V_s sum_i lambda_i grad W(x_i - x_s)
  std::vector<Real> solid_inv_mass;     // 1/kg, per solid sample: this substep's split (split_solid_masses)
  std::vector<Real> solid_share;        // per model particle: 1 / c_k of the split (coupled particles only)
  std::vector<Index> solid_contacts;    // per fluid particle: solid samples it touches
  // Each fluid pair's W_ij and grad W_ij from the density multipliers' pass, read by the
  // corrections' pass (DensityPairCache); row i starts at pair_offset[i] (lay_out_pair_cache).
  std::vector<Index> pair_offset;
  std::vector<Real> pair_w, pair_gx, pair_gy, pair_gz;  // 1/m^3, 1/m^4

  // The implicit viscosity (fluid_viscosity.hpp; empty when it is explicit): the step's velocity
  // change; per particle the gradient correction L (and, next to walls, the one over the fluid
  // neighbours alone), the stress times it S = tau L, the velocity gradient G, the wall terms q and
  // P; the solver's vectors, the inverse diagonal blocks and the per-block partial dot products.
  std::vector<Vec3> viscous_change;     // m/s
  std::vector<Mat3> gradient_correction, fluid_gradient_correction, corrected_stress;
  std::vector<Real> stress_viscosity;   // Pa s, mu_k of the stress (interface_viscosity.hpp)
  std::vector<Vec3> wall_sum;           // 1/m
  std::vector<Mat3> wall_velocity_sum;  // 1/s
  std::vector<Mat3> velocity_gradient;  // 1/s, G_k of the last gradient pass
  // Solid surfaces with fluid friction (empty without): per rigid body with samples its pose and
  // velocities this substep; per solid sample its velocity (cloth, soft bodies, continua) and the viscous
  // force the fluid puts on it; per particle
  // the gradient of its corrected stress, dS/dx_c, that extrapolates it to the samples.
  struct RigidSurfaceMotion {
    Pose pose;
    Vec3 velocity = Vec3::Zero(), angular_velocity = Vec3::Zero();  // m/s, rad/s
  };
  std::vector<RigidSurfaceMotion> rough_body;  // by body index
  std::vector<Vec3> solid_wall_velocity;  // m/s, per particle-borne sample: sum_i b_i v_i of its particles
  std::vector<Vec3> solid_viscous_force;  // N
  std::vector<std::array<Mat3, 3>> stress_slope;
  // BiCGSTAB's vectors: residual r, shadow residual, direction p, A y, preconditioned y (and z),
  // intermediate residual s, A z.
  std::vector<Vec3> solve_residual, solve_shadow, solve_direction, solve_direction_image, solve_preconditioned,
      solve_intermediate, solve_intermediate_image;
  std::vector<Mat3> inverse_diagonal;   // 1/kg
  std::vector<Real> block_sum_a, block_sum_b;
  // The drift's trades (phase_drift.hpp; sized by drift_phases on its first call): per particle
  // the heavier particle it proposes to, how far that one lies above it, whether it has fewer
  // neighbours of its own liquid than of others, and the particle it trades with.
  std::vector<Index> drift_proposal, drift_partner;
  std::vector<Real> drift_rise;         // m
  std::vector<char> drift_minority;

  /// Sizes the buffers for the model's fluid (nothing is reallocated when they already fit).
  void fit(const FluidModel& fluid);
};

}  // namespace moreau
