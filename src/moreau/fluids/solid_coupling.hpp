#pragma once
// Two-way coupling of the fluid with cloth and soft bodies (Macklin et al. 2014, "Unified particle
// physics", sec. 7.1: solid particles enter the fluid's density estimate; here with Akinci
// volumes instead of PBF's tuned factor s).
//
// A solid sample s sits at x_s = sum_k b_k x_k over up to four particles of the solid
// (solid_sampling.hpp). It enters the density constraint of every fluid particle i within h
// like a wall sample, with volume V_s:
//   C_i += V_s W(x_i - x_s),   grad_{x_i} C_i += V_s grad W(x_i - x_s),
//   grad_{x_k} C_i = -b_k V_s grad W(x_i - x_s)              (chain rule through x_s)
// and, unlike a wall, it moves: the multiplier's denominator gains
//   sum_k w_k |grad_{x_k} C_i|^2 = w_s V_s^2 |grad W_is|^2,   w_s = sum_k b_k^2 w_k
// (with the mass split of split_solid_masses below; treating each (fluid particle, sample) pair as
// its own constraint, the cross terms between samples that share particles are left out, as the
// split assumes),
// and the solid particles receive the PBD correction of every such constraint,
//   dx_k = w_k sum_i lambda_i grad_{x_k} C_i = w_k sum_s b_k R_s,   R_s = -V_s sum_i lambda_i grad W(x_i - x_s).
// The fluid particle gets w_i lambda_i V_s grad W_is =: w_i F_is, the solid particles -b_k F_is.
// So m_i dx_i + sum_k m_k dx_k = 0 pair by pair (linear momentum), and the moments cancel too:
// x_i x F_is - sum_k b_k x_k x F_is = (x_i - x_s) x F_is = 0, as F_is is parallel to x_i - x_s.
// R_s is gathered over the reverse lists (fluid particles of each sample) and dx_k over the
// particle -> sample table, so every sum has a fixed order: deterministic for any thread count.
//
// Rigid bodies (Akinci et al. 2012, "Versatile rigid-fluid coupling", with the PBD reaction
// above): a sample is a fixed body-frame point s, at x_s = x_b + q_b s. The pair (i, s) pushes the
// body with -F_is at x_s, a rigid body's response to a positional impulse (Mueller et al. 2020,
// eq. 6-9), summed over the body's samples in their fixed order:
//   dx_b = (1/m) sum_s R_s,   q_b += 1/2 [I^-1 sum_s (x_s - x_b) x R_s, 0] q_b.
// Linear momentum is kept exactly; the moments too, as R_s acts at x_s on the line of x_i - x_s.
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"

namespace moreau {

struct Model;
struct State;

/// The solid side of the Jacobi split. A solid particle k is moved by every density constraint of
/// every fluid particle near any of its samples, c_k of them (tens), each computed as if it were
/// the only one; with light cloth or soft-body particles their sum overshoots by about c_k and the
/// solid rings and tears open. So each constraint sees the particle c_k times heavier:
///   w_s = sum_k b_k^2 w_k / c_k,   c_k = max(1, sum_s b_sk n_s)   (n_s: fluid particles near s)
/// in the multiplier's denominator and in the contact split, the way Unified Particle Physics
/// (Macklin et al. 2014, sec. 4.2) averages corrections over a particle's constraint count. The
/// corrections themselves keep the true masses (dx_k = w_k grad_k C lambda), so momentum is still
/// conserved exactly. Measured without the split: a floating slab bobs at 2 cm/s instead of
/// 0.5 cm/s and a cloth's pins carry 1.6 % less than the load (0.4 % with it).
/// A rigid body is one solid moved by all its samples' constraints, c_b = max(1, sum_s n_s) of
/// them, and its generalised inverse mass at sample s is at most w_bs = 1/m + |s|^2 max(I^-1) for
/// any direction, so its samples get w_s = w_bs / c_b.
/// Once per substep, after the neighbour lists (every thread).
void split_solid_masses(const Model& model, const FluidState& fluid, FluidScratch& scratch);

/// x_s = sum_k b_k x_k for every cloth and soft-body sample, from the model's particle positions,
/// and x_s = x_b + q_b s for every rigid-body sample. Call inside an OpenMP parallel region.
void place_solid_samples(const Model& model, State& state);

/// After project_fluid_density (which left the multipliers in scratch.lambda): the reaction R_s of
/// every sample, then the solid particles' and rigid bodies' corrections. Call inside a parallel
/// region.
void apply_solid_reactions(const Model& model, State& state, FluidScratch& scratch);

/// Keeps fluid particles at least FluidModel::solid_contact_distance from every solid sample: a
/// position-level contact, split by inverse mass and averaged over the particle's contacts,
///   p_is = (d_c - |x_i - x_s|) / (w_i + w_s) n_is / n_i,   dx_i = w_i sum_s p_is,   R_s = -sum_i p_is.
/// The density constraint alone cannot stop a particle with few fluid neighbours (a splash: its
/// own kernel value V W(0) = 1/pi is far from 1, so a single layer of samples only pushes once the
/// particle is nearly through it); the contact is what keeps such particles out. At rest the fluid
/// sits 2r from the samples, beyond d_c = 1.5 r, so the contact does not touch the hydrostatics.
/// Moves fluid and solid particles (fluid particles stay clear of the colliders at `time`). Call
/// inside a parallel region, after the density projection.
void project_solid_contacts(const Model& model, State& state, FluidScratch& scratch, Real time);

}  // namespace moreau
