#pragma once
// Shape matching under the velocity-level formulation: every particle of a cluster is a block of
// three rows C_i = x_i - g_i(x), its offset from its goal (shape_matching/shape_matching.hpp),
// with the compliance 1/(m_i omega^2) of the cluster's energy (0 for a rigid cluster).
//
// The goal g_i = c + R q_i moves with every particle of the cluster, so the block's Jacobian has
// an end per member. With p_j = R q_j, the mass centre c = sum m_j x_j / M and d_j = x_j - c,
// the fit turns at w = K^-1 sum_j m_j p_j x v_j, K = tr(S) I - S, where S = A R^T =
// sum m_j d_j p_j^T is the fit's stretch in the world frame: writing dR = [dtheta]x R and
// A = R S0 (S0 symmetric), the skew part of R^T dA is 1/2 [(tr S0 I - S0) R^T dtheta]x, and that
// of R^T dA = sum m_j R^T dx_j q_j^T is 1/2 [sum m_j q_j x R^T dx_j]x, so
// (tr S I - S) dtheta = sum m_j p_j x dx_j. For a rigid placement K is the cluster's inertia
// tensor and w its angular velocity. A cluster on a line (a clump's pair) has none about that
// line, where turning moves nothing: K^-1 is then K's pseudo-inverse.
//
// The rows are the offsets measured in the turning fit's frame, C_i = R (R^T d_i - q_i), whose
// rate is v_i - v_c - w x d_i: the exact rate of x_i - g_i less w x C_i, the offset turning with
// the fit. The block for end j is therefore
//   J_ij = (delta_ij - m_j / M) I + m_j [d_i]x K^-1 [p_j]x.
// Every rigid motion of the cluster is then exactly free (its velocities v_j = u + w x d_j make
// K^-1 sum m_j p_j x (w x d_j) = K^-1 K w = w, so every row's rate is 0), and the 3n rows of a
// rigid cluster repeat each other exactly 6 times, along (m_i a) and (m_i b x p_i), on which C
// vanishes (sum m_i C_i = 0, and sum m_i p_i x C_i = 0 as S is symmetric), so the factored
// methods solve them as they are. With the exact gradient's arm p_i instead of d_i, a spinning
// rigid cube lost its spin within a second under those methods: the rows then ask w x C_i of the
// spin through directions that are nearly, not exactly, free. The two give the same force
// -m_i omega^2 J^T C (the difference [C_i]x B_j leaves C_i x C_i = 0). The rows' impulses sum to
// zero force (sum_j J_ij = [d_i]x K^-1 [sum_j m_j p_j]x = 0), so they keep the cluster's
// momentum. A cluster of n particles makes n blocks over n ends: its rows cost
// n^2 Jacobian entries, so clusters are kept small (shape-matched objects split into clusters).
#include <vector>

#include "moreau/model/state.hpp"
#include "moreau/solvers/nmd/nmd_system.hpp"

namespace moreau {

/// Adds the blocks of every cluster at the state's positions, warm-started from `memory` (one
/// impulse per cluster entry, resized here); `in` is the block's scratch. A pinned particle has no
/// block of its own (its goal pulls nothing), but its velocity still moves the others' goals.
void add_shape_match_rows(const Model& model, const State& state, const VelocitySpace& space, Real h, NmdBlockInput& in,
                          NmdSystem& system, std::vector<Vec3>& memory);

}  // namespace moreau
