#pragma once
// XPBD projections of the particle constraint families: one Gauss-Seidel sweep by colour, with
// lambda accumulating over the iterations of a substep. Each is a closed form of the generic row
// projection (project_rows.hpp) that keeps the family's gradients in registers; a family without
// one here is projected by the generic template, so a new family needs no XPBD code at all.
// Call from inside an OpenMP parallel region (or serially).
#include "moreau/constraints/particle_families.hpp"
#include "moreau/solvers/xpbd/project_rows.hpp"
#include "moreau/solvers/xpbd/substep_context.hpp"

namespace moreau {

void xpbd_project(const DistanceConstraints& c, Real* lambda, const SubstepContext& s);
void xpbd_project(const DihedralBendingConstraints& c, Real* lambda, const SubstepContext& s);
void xpbd_project(const IsometricBendingConstraints& c, Vec3* lambda, const SubstepContext& s);
void xpbd_project(const TriangleStrainConstraints& c, Vec3* lambda, const SubstepContext& s);
void xpbd_project(const NeoHookeanTetConstraints& c, Vec2* lambda, const SubstepContext& s);
void xpbd_project(const TetVolumeConstraints& c, Real* lambda, const SubstepContext& s);
void xpbd_project(const AttachmentConstraints& c, Vec3* lambda, const SubstepContext& s);

}  // namespace moreau
