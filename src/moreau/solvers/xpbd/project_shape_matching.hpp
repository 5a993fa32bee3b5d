#pragma once
// XPBD's projection of the shape-matching clusters (shape_matching/shape_matching.hpp): each
// cluster in turn, Gauss-Seidel, every particle moved the share s of the way to its goal.
#include "moreau/solvers/xpbd/substep_context.hpp"

namespace moreau {

struct Model;

/// One pass over every cluster; call from one thread (clusters overlap).
void project_shape_matching(const Model& model, const SubstepContext& s);

}  // namespace moreau
