// FEM building blocks against their defining properties: shape functions (partition of unity,
// nodal interpolation), Gauss rules (exact integrals of monomials), the hyperelastic stress and
// tangent (derivatives of the energy), the assembled tangent (derivative of the internal forces)
// and the patch test.
#include <gtest/gtest.h>

#include <cmath>

#include "fem_test_helpers.hpp"
#include "moreau/fem/solids/static_solver.hpp"

namespace moreau {
namespace {

const ElementType kCells[] = {ElementType::tri3, ElementType::quad4, ElementType::tet4, ElementType::hex8};

// Reference node coordinates of each element (for nodal interpolation).
std::vector<Vec3> reference_nodes(ElementType type) {
  switch (type) {
    case ElementType::line2: return {Vec3(-1, 0, 0), Vec3(1, 0, 0)};
    case ElementType::tri3: return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    case ElementType::quad4: return {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
    case ElementType::tet4: return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    case ElementType::hex8:
      return {Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(-1, 1, -1),
              Vec3(-1, -1, 1),  Vec3(1, -1, 1),  Vec3(1, 1, 1),  Vec3(-1, 1, 1)};
  }
  return {};
}

TEST(FemElements, ShapeFunctionsInterpolateAndSumToOne) {
  // N_a(xi_b) = delta_ab; sum_a N_a = 1 and sum_a dN_a = 0 anywhere; dN matches central
  // differences of N (to 1e-9: the functions are at most trilinear, so only round-off remains).
  for (ElementType type : {ElementType::line2, ElementType::tri3, ElementType::quad4, ElementType::tet4, ElementType::hex8}) {
    const auto nodes = reference_nodes(type);
    const int n = element_node_count(type);
    Real N[kMaxElementNodes], Np[kMaxElementNodes], Nm[kMaxElementNodes];
    Vec3 dN[kMaxElementNodes], scratch[kMaxElementNodes];
    for (int b = 0; b < n; ++b) {
      shape_functions(type, nodes[b], N, dN);
      for (int a = 0; a < n; ++a) EXPECT_NEAR(N[a], a == b ? 1.0 : 0.0, 1e-15) << element_name(type);
    }
    const Vec3 xi = Vec3(0.21, 0.17, 0.13).head(3);
    shape_functions(type, xi, N, dN);
    Real sum = 0;
    Vec3 dsum = Vec3::Zero();
    for (int a = 0; a < n; ++a) sum += N[a], dsum += dN[a];
    EXPECT_NEAR(sum, 1.0, 1e-15) << element_name(type);
    EXPECT_LT(dsum.norm(), 1e-15) << element_name(type);
    const Real h = 1e-6;
    for (int k = 0; k < element_dimension(type); ++k) {
      shape_functions(type, xi + h * Vec3::Unit(k), Np, scratch);
      shape_functions(type, xi - h * Vec3::Unit(k), Nm, scratch);
      for (int a = 0; a < n; ++a) EXPECT_NEAR(dN[a][k], (Np[a] - Nm[a]) / (2 * h), 1e-9) << element_name(type);
    }
  }
}

TEST(FemElements, GaussRulesIntegrateMonomialsExactly) {
  // Reference-element integrals of x^i y^j z^k with i + j + k <= degree: on [-1, 1]^d the product of
  // 2/(i+1) (i even) or 0; on the simplex i! j! k! / (i + j + k + d)!.
  auto factorial = [](int n) { Real f = 1; for (int i = 2; i <= n; ++i) f *= i; return f; };
  for (ElementType type : kCells) {
    const int d = element_dimension(type);
    const bool simplex = type == ElementType::tri3 || type == ElementType::tet4;
    for (int degree = 1; degree <= (type == ElementType::tet4 ? 2 : 3); ++degree) {
      const auto rule = gauss_rule(type, degree);
      for (int i = 0; i <= degree; ++i)
        for (int j = 0; i + j <= degree; ++j)
          for (int k = 0; i + j + k <= degree; ++k) {
            if (d == 2 && k > 0) continue;
            Real quadrature = 0;
            for (const auto& q : rule)
              quadrature += q.weight * std::pow(q.xi.x(), i) * std::pow(q.xi.y(), j) * std::pow(q.xi.z(), k);
            Real exact;
            if (simplex) {
              exact = factorial(i) * factorial(j) * factorial(k) / factorial(i + j + k + d);
            } else {
              auto line = [](int p) { return p % 2 ? 0.0 : 2.0 / (p + 1); };
              exact = line(i) * line(j) * (d == 3 ? line(k) : 1.0);
            }
            EXPECT_NEAR(quadrature, exact, 1e-14) << element_name(type) << " degree " << degree << " x^" << i
                                                  << " y^" << j << " z^" << k;
          }
    }
  }
}

TEST(FemMaterials, StressAndTangentAreDerivativesOfTheEnergy) {
  // S = dW/dE and CC = dS/dE by central differences with step 1e-6 on E: the truncation error is
  // ~1e-12 relative and round-off ~1e-10, so 1e-7 relative separates a right formula from a wrong
  // factor or sign. Checked at a moderate and a large deformation (stretch 1.8, shear 0.5).
  Mat3 H1;
  H1 << 0.05, 0.1, 0.02, -0.03, -0.03, 0.08, 0.01, -0.05, 0.1;
  Mat3 H2;
  H2 << 0.8, 0.5, 0.0, 0.1, -0.3, 0.2, -0.3, 0.0, 0.2;
  for (HyperelasticModel model : {HyperelasticModel::neo_hookean, HyperelasticModel::st_venant_kirchhoff}) {
    const HyperelasticMaterial m = test::fem_material(model, 2e6, 0.35);
    for (const Mat3& H : {H1, H2}) {
      const Mat3 E = green_lagrange_strain(H);
      const Mat3 F = Mat3::Identity() + H;
      EXPECT_LT((E - 0.5 * (F.transpose() * F - Mat3::Identity())).norm(), 1e-15);
      const HyperelasticResponse r = m.respond(E);
      const Real h = 1e-6;
      static const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
      for (int q = 0; q < 6; ++q) {
        Mat3 dE = Mat3::Zero();
        dE(pairs[q][0], pairs[q][1]) = dE(pairs[q][1], pairs[q][0]) = h;
        // dW = S : dE: a diagonal step gives S_II h, an off-diagonal one (both entries) 2 S_IJ h;
        // in Voigt form the step is dE_q = h (diagonal) or 2h (engineering shear).
        const Real step = q < 3 ? h : 2 * h;
        const Real S_fd = (m.energy(E + dE) - m.energy(E - dE)) / (2 * step);
        EXPECT_NEAR(r.stress[q], S_fd, 1e-7 * r.stress.norm()) << "S component " << q;
        const Vec6 column = (to_voigt(m.stress(E + dE)) - to_voigt(m.stress(E - dE))) / (2 * step);
        EXPECT_LT((r.tangent.col(q) - column).norm(), 1e-7 * r.tangent.norm()) << "CC column " << q;
      }
      EXPECT_LT((r.tangent - r.tangent.transpose()).norm(), 1e-12 * r.tangent.norm());
    }
    // At E = 0 both reduce to linear elasticity: CC = lambda I(x)I + 2 mu II; and at a strain of
    // 1e-9 the stress is CC : E to 1e-6 relative (no digits lost to cancellation: a formula in
    // C - I would keep only ~7 of them there).
    const HyperelasticResponse r0 = m.respond(Mat3::Zero());
    EXPECT_EQ(r0.energy, 0.0);
    EXPECT_EQ(r0.stress.norm(), 0.0);
    EXPECT_NEAR(r0.tangent(0, 0), m.lame.lambda + 2 * m.lame.mu, 1e-9 * m.lame.mu);
    EXPECT_NEAR(r0.tangent(0, 1), m.lame.lambda, 1e-9 * m.lame.mu);
    EXPECT_NEAR(r0.tangent(3, 3), m.lame.mu, 1e-9 * m.lame.mu);
    const Mat3 tiny = 1e-9 * green_lagrange_strain(H1) / green_lagrange_strain(H1).norm();
    Vec6 tiny_voigt = to_voigt(tiny);
    tiny_voigt.tail<3>() *= 2;
    const Vec6 linear = r0.tangent * tiny_voigt;
    EXPECT_LT((m.respond(tiny).stress - linear).norm(), 1e-6 * linear.norm());
  }
}

// A small distorted mesh of each cell type: 3 x 3 (x 3) cells of 0.1 m.
FemMesh distorted_mesh(ElementType type) {
  FemMesh mesh = element_dimension(type) == 2
                     ? make_rectangle_mesh(Vec2(0, 0), Vec2(0.3, 0.3), {3, 3}, type)
                     : make_box_mesh(Vec3(0, 0, 0), Vec3(0.3, 0.3, 0.3), {3, 3, 3}, type);
  test::distort_interior(mesh, 0.25, 0.1);
  return mesh;
}

TEST(FemAssembly, TangentIsTheDerivativeOfTheInternalForces) {
  // K = d f_int / du by central differences (step 1e-7 m on 0.1 m cells) at a random displacement
  // of up to 3 cm (strains ~ 0.3), every cell type and both materials; all dofs free. Agreement to
  // 1e-6 of |K|: truncation ~1e-12, round-off ~|f| 1e-16 / 1e-7 ~ 1e-9 |K|.
  for (ElementType type : kCells)
    for (HyperelasticModel law : {HyperelasticModel::neo_hookean, HyperelasticModel::st_venant_kirchhoff}) {
      FemModel model;
      model.dim = element_dimension(type);
      add_fem_solid(model, test::fem_solid("s", distorted_mesh(type), test::fem_material(law, 1e6, 0.3)));
      finalize_fem_model(model);
      std::mt19937 rng(3);
      std::uniform_real_distribution<Real> dist(-0.03, 0.03);
      VectorX u(model.dof_count());
      for (Index i = 0; i < u.size(); ++i) u[i] = dist(rng);
      VectorX f, fp;
      SparseMatrix K;
      ASSERT_TRUE(assemble_internal_forces(model, u, f, &K).valid);
      const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
      const Real worst = test::jacobian_error(Kd, u, 1e-7, [&](const VectorX& v) {
        assemble_internal_forces(model, v, fp, nullptr);
        return fp;
      });
      EXPECT_LT(worst, 1e-6 * Kd.cwiseAbs().maxCoeff()) << element_name(type) << " " << static_cast<int>(law);
      EXPECT_LT((Kd - Kd.transpose()).cwiseAbs().maxCoeff(), 1e-9 * Kd.cwiseAbs().maxCoeff());
    }
}

TEST(FemAssembly, StepTangentsAreDerivativesOfTheStepForces) {
  // The step forces of the midpoint rule and the energy-momentum scheme between u_n and u_next
  // (random, up to 3 cm on 0.1 m cells), differentiated in u_next by central differences (step
  // 1e-7): the midpoint tangent is exact and symmetric; the energy-momentum tangent, with the
  // discrete-gradient correction's derivative, exact and not symmetric. Same tolerance as above.
  for (ElementType type : {ElementType::quad4, ElementType::hex8, ElementType::tet4})
    for (StepRule rule : {StepRule::midpoint, StepRule::energy_momentum}) {
      FemModel model;
      model.dim = element_dimension(type);
      add_fem_solid(model, test::fem_solid("s", distorted_mesh(type), test::fem_material(HyperelasticModel::neo_hookean, 1e6, 0.3)));
      finalize_fem_model(model);
      std::mt19937 rng(5);
      std::uniform_real_distribution<Real> dist(-0.03, 0.03);
      VectorX u0(model.dof_count()), u1(model.dof_count());
      for (Index i = 0; i < u0.size(); ++i) u0[i] = dist(rng), u1[i] = dist(rng);
      VectorX f, fp;
      SparseMatrix K;
      ASSERT_TRUE(assemble_step_forces(model, u0, u1, rule, f, &K).valid);
      const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
      const Real worst = test::jacobian_error(Kd, u1, 1e-7, [&](const VectorX& v) {
        assemble_step_forces(model, u0, v, rule, fp, nullptr);
        return fp;
      });
      EXPECT_LT(worst, 1e-6 * Kd.cwiseAbs().maxCoeff()) << element_name(type) << " rule " << static_cast<int>(rule);
    }
}

TEST(FemAssembly, PatchTestReproducesAHomogeneousDeformationExactly) {
  // Boundary nodes displaced by u = A X + b on a distorted mesh: the exact solution is the
  // homogeneous deformation F = I + A everywhere (uniform stress, no body force), which every
  // conforming element must reproduce at the interior nodes. A is finite (up to 20 % strain), so
  // this is the patch test of the nonlinear formulation; Newton's tolerance 1e-12 leaves errors
  // ~1e-13 m. Also reports the convergence of Newton from u = 0 (quadratic: at most 6 solves).
  Mat3 A;
  A << 0.12, 0.05, -0.03, -0.04, -0.08, 0.06, 0.02, 0.07, 0.2;
  const Vec3 b(0.01, -0.02, 0.005);
  for (ElementType type : kCells) {
    FemModel model;
    model.dim = element_dimension(type);
    add_fem_solid(model, test::fem_solid("s", distorted_mesh(type), test::fem_material(HyperelasticModel::neo_hookean, 1e6, 0.3)));
    Mat3 Aused = A;  // in 2D only the in-plane part
    if (model.dim == 2) {
      Aused.setZero();
      Aused.topLeftCorner<2, 2>() = A.topLeftCorner<2, 2>();
    }
    std::vector<Index> exterior = exterior_facets(model.solids[0].mesh);
    std::sort(exterior.begin(), exterior.end());
    exterior.erase(std::unique(exterior.begin(), exterior.end()), exterior.end());
    test::prescribe_nodes(model, exterior, [&](const Vec3& X) { return Vec3(Aused * X + b); });
    finalize_fem_model(model);
    VectorX u = VectorX::Zero(model.dof_count());
    SparseSymmetricSolver solver;
    const NewtonResult r = solve_static(model, 1.0, u, solver, {.tolerance = 1e-12});
    ASSERT_TRUE(r.converged) << element_name(type) << ": " << r.failure;
    EXPECT_LE(r.iterations, 6) << element_name(type);
    Real worst = 0;
    for (Index n = 0; n < model.node_count; ++n) {
      const Vec3 exact = Aused * model.reference_position(n) + b;
      for (int k = 0; k < model.dim; ++k) worst = std::max(worst, std::abs(u[model.dof(n, k)] - exact[k]));
    }
    EXPECT_LT(worst, 1e-11) << element_name(type);
  }
}

}  // namespace
}  // namespace moreau
