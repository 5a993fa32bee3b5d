#pragma once
// The end of an XPBI step for the continuum's particles (Yu et al. 2024, Alg. 1, after the
// iterations), once the substep has set v = (x - x^n) / h:
//   XSPH (eq. 20):  v_p += c sum_b Vbar_pb (v_b - v_p - (grad v_p + grad v_b)/2 (x_b - x_p)) W_pb,
//                   with Vbar_pb = (V_b + (m_b / m_p) V_p) / 2 (V_b for one density). The paper
//                   smooths v_b - v_p itself; here the pair's mean linear field is taken out first,
//                   so that only the disorder beyond it is smoothed. Inside the body sum V W (x_b - x_p)
//                   vanishes and the two agree; at its surface the paper's form drags every linear
//                   motion, a spin included (a free 8 x 6 x 7 cm block at 10 rad/s kept 78 % of its
//                   angular momentum after 0.5 s at 0.5 ms substeps, and 41 % at 0.125 ms). Each
//                   pair's terms are equal and opposite, so the momentum is kept;
//   positions:      x_p = x_p^n + h v_p, with the smoothed velocity;
//   deformation:    F_p^{n+1} = Z((I + h grad v_p) F_p^n) (eq. 22) with that same velocity; the
//                   flow's plastic strain is added up and snow's J_p grows by its volume factor;
//   packing:        where the particles pack more than 10 % closer than det F holds, F's volume
//                   follows them (continuum/packing_volume.hpp; settings.xpbi.packing_volume).
#include <vector>

#include "moreau/solvers/xpbd/substep_context.hpp"
#include "moreau/solvers/xpbi/continuum_neighborhood.hpp"

namespace moreau {

/// Per continuum particle: its velocity gradient (1/s) and smoothed velocity (m/s).
struct ContinuumSubstepScratch {
  std::vector<Mat3> velocity_gradient;
  std::vector<Vec3> smoothed;
};

/// Every thread of a parallel region calls it; `scratch` is sized for the continuum.
void finish_continuum_substep(const Model& model, State& state, const ContinuumNeighborhood& around,
                              const SubstepContext& ctx, ContinuumSubstepScratch& scratch);

}  // namespace moreau
