// One XPBD projection per constraint family, checked against a computation done by hand (the
// arithmetic is in each test's comment). Substep h = 0.1 s, so alpha~ = alpha / h^2 = 100 alpha.
// Each case runs twice: with the family's closed-form XPBD kernel and with the generic projection
// of its rows (project_rows.hpp), so both the kernel and the family's rows are checked.
// These are exact rational or closed-form values; 1e-12 only allows for round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "moreau/constraints/attachment.hpp"
#include "moreau/constraints/dihedral_bending.hpp"
#include "moreau/constraints/distance.hpp"
#include "moreau/constraints/neo_hookean_tet.hpp"
#include "moreau/constraints/tet_volume.hpp"
#include "moreau/constraints/triangle_strain.hpp"
#include "moreau/solvers/xpbd/particle_projections.hpp"

using namespace moreau;

namespace {
constexpr Real kH = 0.1;
constexpr Real kTol = 1e-12;

enum class Kernel { closed_form, generic_rows };
constexpr std::array<Kernel, 2> kKernels{Kernel::closed_form, Kernel::generic_rows};
const char* kernel_name(Kernel k) { return k == Kernel::closed_form ? "closed-form kernel" : "generic row projection"; }

template <class Family>
void project(Kernel kernel, const Family& c, typename Family::Multiplier* lambda, const SubstepContext& s) {
  if (kernel == Kernel::closed_form)
    xpbd_project(c, lambda, s);
  else
    for_each_by_color(c.batches, [&](Index k) { xpbd_project_rows(c, k, lambda[k], s); });
}
const std::array<Vec3, 4> kUnitTet{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
}  // namespace

TEST(ProjectionByHand, Distance) {
  for (const Kernel kernel : kKernels) {
    SCOPED_TRACE(kernel_name(kernel));
    // a = 0 (w 1), b = (2,0,0) (w 3), rest 1, alpha 0.01 -> alpha~ = 1. C = 1, n = (-1,0,0).
    // dlambda = -C / (w_a + w_b + alpha~) = -0.2; x_a += w_a dl n = (0.2,0,0); x_b -= w_b dl n -> (1.4,0,0).
    std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(2, 0, 0)};
    const std::vector<Vec3> start = x;
    std::vector<Real> w{1, 3}, lambda(1, 0);
    DistanceConstraints c;
    c.add(0, 1, 1.0, 0.01, 0, 0);
    c.color(w);
    project(kernel, c, lambda.data(), SubstepContext{x.data(), start.data(), w.data(), kH});
    EXPECT_NEAR(x[0].x(), 0.2, kTol);
    EXPECT_NEAR(x[1].x(), 1.4, kTol);
    EXPECT_NEAR(lambda[0], -0.2, kTol);
  }
}

TEST(ProjectionByHand, DihedralBending) {
  for (const Kernel kernel : kKernels) {
    SCOPED_TRACE(kernel_name(kernel));
    // Flat rest hinge e0 = 0, e1 = (1,0,0), o0 = (0.5,0,1), o1 = (0.5,0,-1); o0 lifted to y = 0.1, only
    // o0 free (w 1), alpha 0. nA = e x (o0 - e0) = (0,-1,0.1), nB = (o1 - e0) x e = (0,-1,0):
    // theta = atan2((nA x nB).e, nA.nB) = atan2(0.1, 1); grad_o0 = -nA/|nA|^2 with |nA|^2 = 1.01.
    // dlambda = -theta/|grad|^2 = -1.01 theta, dx = dlambda grad = theta nA = theta (0,-1,0.1).
    std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, 1), Vec3(0.5, 0, -1)};
    std::vector<Real> w{0, 0, 1, 0}, lambda(1, 0);
    DihedralBendingConstraints c;
    c.add({0, 1, 2, 3}, 0.0, 0.0, 0.0, 0);
    c.color(w);
    x[2].y() = 0.1;
    const std::vector<Vec3> start = x;
    project(kernel, c, lambda.data(), SubstepContext{x.data(), start.data(), w.data(), kH});
    const Real theta = std::atan2(0.1, 1.0);
    EXPECT_NEAR(x[2].x(), 0.5, kTol);
    EXPECT_NEAR(x[2].y(), 0.1 - theta, kTol);
    EXPECT_NEAR(x[2].z(), 1 + 0.1 * theta, kTol);
    EXPECT_NEAR(lambda[0], -1.01 * theta, kTol);
  }
}

TEST(ProjectionByHand, TriangleStrainMembrane) {
  for (const Kernel kernel : kKernels) {
    SCOPED_TRACE(kernel_name(kernel));
    // Rest right triangle X0 = 0, X1 = (1,0,0), X2 = (0,1,0): D_m = I, A = 1/2. E = 200 Pa, nu = 0,
    // t = 1 m: K = diag(E, E, E/2), alpha = (A t K)^-1 = diag(1, 1, 2)/100, alpha~ = diag(1, 1, 2).
    // x1 stretched to (2,0,0), only x1 free (w 1): f1 = (2,0,0), f2 = (0,1,0), C = (3/2, 0, 0);
    // grad_x1 rows: E11 -> f1 = (2,0,0), E22 -> 0, 2E12 -> f2 = (0,1,0), so J W J^T = diag(4, 0, 1),
    // A = diag(5, 1, 3), dlambda = -(3/2, 0, 0)/A = (-0.3, 0, 0), dx1 = J^T dlambda = (-0.6, 0, 0).
    std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    std::vector<Real> w{0, 1, 0};
    std::vector<Vec3> lambda(1, Vec3::Zero());
    TriangleStrainConstraints c;
    c.add({0, 1, 2}, x[0], x[1], x[2], 200, 0.0, 1.0, 0.0, 0);
    c.color(w);
    x[1].x() = 2;
    const std::vector<Vec3> start = x;
    project(kernel, c, lambda.data(), SubstepContext{x.data(), start.data(), w.data(), kH});
    EXPECT_NEAR((x[1] - Vec3(1.4, 0, 0)).norm(), 0, kTol);
    EXPECT_NEAR((lambda[0] - Vec3(-0.3, 0, 0)).norm(), 0, kTol);
  }
}

TEST(ProjectionByHand, TetVolume) {
  for (const Kernel kernel : kKernels) {
    SCOPED_TRACE(kernel_name(kernel));
    // Unit right tetrahedron (V0 = 1/6) with x3 pulled to (0,0,2): J = 2, C = 1. Only x3 free, alpha 0.
    // grad_x3 C = (x1 - x0) x (x2 - x0) / (6 V0) = (0,0,1); dlambda = -1; x3 -> (0,0,1), exactly (C is
    // linear in x3).
    std::vector<Vec3> x(kUnitTet.begin(), kUnitTet.end());
    std::vector<Real> w{0, 0, 0, 1}, lambda(1, 0);
    TetVolumeConstraints c;
    c.add({0, 1, 2, 3}, kUnitTet, 0.0, 0.0, 0);
    c.color(w);
    x[3].z() = 2;
    const std::vector<Vec3> start = x;
    project(kernel, c, lambda.data(), SubstepContext{x.data(), start.data(), w.data(), kH});
    EXPECT_NEAR((x[3] - Vec3(0, 0, 1)).norm(), 0, kTol);
    EXPECT_NEAR(lambda[0], -1, kTol);
  }
}

TEST(ProjectionByHand, NeoHookeanCoupledPair) {
  for (const Kernel kernel : kKernels) {
    SCOPED_TRACE(kernel_name(kernel));
    // Unit right tetrahedron (V0 = 1/6, D_m = I), E = 1200 Pa, nu = 0: mu = 600, lambda_Lame = 0, so the
    // stable Neo-Hookean lambda = 600 and gamma = 1 + mu/lambda = 2. alpha_H = 1/(lambda V0) = 0.01 and
    // alpha_D = 1/(mu V0) = 0.01, so both alpha~ = 1. x1 stretched to (2,0,0), only x1 free (w 1):
    // F = diag(2,1,1): C_H = det F - gamma = 0, C_D = |F| = sqrt(6); grad_x1 C_H = (1,0,0),
    // grad_x1 C_D = (2,0,0)/sqrt(6). System [[1+1, 2/sqrt6], [2/sqrt6, 4/6+1]] dl = -(0, sqrt6):
    // det = 10/3 - 2/3 = 8/3, dl_H = (2/sqrt6 * sqrt6)/(8/3) = 3/4, dl_D = -2 sqrt6/(8/3) = -3 sqrt6/4,
    // dx1 = 3/4 (1,0,0) - 3 sqrt6/4 (2/sqrt6, 0, 0) = (-3/4, 0, 0): x1 -> (1.25, 0, 0).
    std::vector<Vec3> x(kUnitTet.begin(), kUnitTet.end());
    std::vector<Real> w{0, 1, 0, 0};
    std::vector<Vec2> lambda(1, Vec2::Zero());
    NeoHookeanTetConstraints c;
    c.add({0, 1, 2, 3}, kUnitTet, 1200, 0.0, 0.0, 0);
    c.color(w);
    x[1].x() = 2;
    const std::vector<Vec3> start = x;
    project(kernel, c, lambda.data(), SubstepContext{x.data(), start.data(), w.data(), kH});
    EXPECT_NEAR((x[1] - Vec3(1.25, 0, 0)).norm(), 0, kTol);
    EXPECT_NEAR(lambda[0].x(), 0.75, kTol);
    EXPECT_NEAR(lambda[0].y(), -0.75 * std::sqrt(6.0), kTol);
  }
}

TEST(ProjectionByHand, CompliantAttachment) {
  for (const Kernel kernel : kKernels) {
    SCOPED_TRACE(kernel_name(kernel));
    // x = (1,0,0), pin at 0, w = 2, alpha 0.01 -> alpha~ = 1: dlambda = -C/(w + alpha~) = -(1,0,0)/3,
    // dx = w dlambda: x -> (1/3, 0, 0).
    std::vector<Vec3> x{Vec3(1, 0, 0)};
    const std::vector<Vec3> start = x;
    std::vector<Real> w{2};
    std::vector<Vec3> lambda(1, Vec3::Zero());
    AttachmentConstraints c;
    c.add(0, Vec3::Zero(), 0.01, 0, 0);
    c.color(w);
    project(kernel, c, lambda.data(), SubstepContext{x.data(), start.data(), w.data(), kH});
    EXPECT_NEAR((x[0] - Vec3(1.0 / 3, 0, 0)).norm(), 0, kTol);
  }
}
