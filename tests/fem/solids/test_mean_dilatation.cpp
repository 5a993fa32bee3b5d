// The mean-dilatation element (fem/solids/mean_dilatation): its force is the derivative of its
// energy and its tangent the derivative of its force (static, midpoint and energy-momentum steps),
// an energy-momentum step's force does exactly the work of the energy change and keeps angular
// momentum, a homogeneous deformation gives the displacement element's result (patch test), and the
// output stresses carry the cell's pressure.
#include <gtest/gtest.h>

#include <random>

#include "moreau/fem/scene/fem_output.hpp"
#include "moreau/fem/solids/fem_model.hpp"
#include "moreau/fem/solids/solid_element.hpp"

namespace moreau {
namespace {

// One distorted quad4 or hex8 cell of a nearly incompressible Neo-Hookean solid (lambda/mu = 5e3).
FemSolid distorted_cell(int dim) {
  FemModel model;
  model.dim = dim;
  FemSolid solid;
  solid.name = "cell";
  solid.mesh = dim == 2 ? make_rectangle_mesh(Vec2(0, 0), Vec2(1.2, 0.8), {1, 1}, ElementType::quad4)
                        : make_box_mesh(Vec3(0, 0, 0), Vec3(1.2, 0.8, 1), {1, 1, 1}, ElementType::hex8);
  std::mt19937 random(3);
  std::uniform_real_distribution<Real> unit(-0.15, 0.15);
  for (Vec3& x : solid.mesh.nodes)
    for (int k = 0; k < dim; ++k) x[k] += unit(random);
  solid.material.lame = {5e3, 1.0};
  solid.material.density = 1;
  solid.volume = VolumeTreatment::mean_dilatation;
  add_fem_solid(model, std::move(solid));
  finalize_fem_model(model);
  return model.solids[0];
}

std::vector<Real> random_displacement(int n, Real size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> unit(-size, size);
  std::vector<Real> u(n);
  for (Real& x : u) x = unit(random);
  return u;
}

ElementOutput at(const FemSolid& s, int dim, const std::vector<Real>& u, bool tangent) {
  ElementOutput out;
  solid_element(s.material, s.volume, s.cell_quadrature(0), dim, u.data(), tangent, out);
  return out;
}

ElementOutput step(const FemSolid& s, int dim, const std::vector<Real>& u_n, const std::vector<Real>& u_next,
                   StepRule rule, bool tangent) {
  ElementOutput out;
  solid_element_step(s.material, s.volume, s.cell_quadrature(0), dim, u_n.data(), u_next.data(), rule, tangent, out);
  return out;
}

// Largest |exact - central difference| over the entries, relative to the largest entry.
template <class Value, class Exact>
Real largest_difference(int n, const std::vector<Real>& u, Value value, const Exact& exact) {
  const Real h = 1e-6;
  Real worst = 0, scale = 0;
  for (int j = 0; j < n; ++j) {
    std::vector<Real> plus = u, minus = u;
    plus[j] += h;
    minus[j] -= h;
    const Eigen::VectorXd difference = (value(plus) - value(minus)) / (2 * h);
    const Eigen::VectorXd column = exact(j);
    worst = std::max(worst, (column - difference).lpNorm<Eigen::Infinity>());
    scale = std::max(scale, column.lpNorm<Eigen::Infinity>());
  }
  return worst / scale;
}

TEST(MeanDilatation, ForceIsTheEnergysGradientAndTangentTheForcesDerivative) {
  // Central differences with h = 1e-6 on displacements of 0.1 of the cell are exact to ~1e-8 of
  // the entries (the volumetric stiffness is 5e3 times the shear's; round-off is below that).
  for (int dim : {2, 3}) {
    const FemSolid s = distorted_cell(dim);
    const int n = s.mesh.nodes_per_cell() * dim;
    const std::vector<Real> u = random_displacement(n, 0.1, 11);
    const ElementOutput out = at(s, dim, u, true);
    ASSERT_TRUE(out.valid);
    auto energy = [&](const std::vector<Real>& v) { return Eigen::VectorXd::Constant(1, at(s, dim, v, false).energy); };
    const Real force_error = largest_difference(n, u, energy, [&](int j) { return Eigen::VectorXd::Constant(1, out.force[j]); });
    auto force = [&](const std::vector<Real>& v) { return Eigen::VectorXd(at(s, dim, v, false).force); };
    const Real tangent_error = largest_difference(n, u, force, [&](int j) { return Eigen::VectorXd(out.tangent.col(j)); });
    std::printf("mean dilatation %dD: force vs dW/du %.2e, tangent vs df/du %.2e, tangent asymmetry %.2e\n", dim,
                force_error, tangent_error, (out.tangent - out.tangent.transpose()).norm() / out.tangent.norm());
    EXPECT_LT(force_error, 1e-6);
    EXPECT_LT(tangent_error, 1e-6);
    EXPECT_LT((out.tangent - out.tangent.transpose()).norm(), 1e-12 * out.tangent.norm());
  }
}

TEST(MeanDilatation, StepTangentsAreTheDerivativesOfTheStepForces) {
  for (int dim : {2, 3})
    for (StepRule rule : {StepRule::midpoint, StepRule::energy_momentum}) {
      const FemSolid s = distorted_cell(dim);
      const int n = s.mesh.nodes_per_cell() * dim;
      const std::vector<Real> u_n = random_displacement(n, 0.1, 5), u_next = random_displacement(n, 0.1, 6);
      const ElementOutput out = step(s, dim, u_n, u_next, rule, true);
      ASSERT_TRUE(out.valid);
      auto force = [&](const std::vector<Real>& v) { return Eigen::VectorXd(step(s, dim, u_n, v, rule, false).force); };
      const Real error = largest_difference(n, u_next, force, [&](int j) { return Eigen::VectorXd(out.tangent.col(j)); });
      std::printf("mean dilatation %dD, %s step: tangent vs df/du_n+1 %.2e\n", dim,
                  rule == StepRule::midpoint ? "midpoint" : "energy-momentum", error);
      EXPECT_LT(error, 1e-6);
    }
}

TEST(MeanDilatation, AnEnergyMomentumStepDoesTheWorkOfTheEnergyChangeAndKeepsAngularMomentum) {
  // f . (u_n+1 - u_n) = Pi(u_n+1) - Pi(u_n) to round-off (the discrete gradient), and the moment
  // of the forces about the origin at the midpoint configuration, sum x_mid x f, vanishes (S is
  // symmetric): both to 1e-12 of |f| (displacements and coordinates are of order 1).
  for (int dim : {2, 3}) {
    const FemSolid s = distorted_cell(dim);
    const int nodes = s.mesh.nodes_per_cell(), n = nodes * dim;
    const std::vector<Real> u_n = random_displacement(n, 0.1, 8), u_next = random_displacement(n, 0.1, 9);
    const ElementOutput out = step(s, dim, u_n, u_next, StepRule::energy_momentum, false);
    const Real work = [&] {
      Real w = 0;
      for (int i = 0; i < n; ++i) w += out.force[i] * (u_next[i] - u_n[i]);
      return w;
    }();
    const Real change = at(s, dim, u_next, false).energy - at(s, dim, u_n, false).energy;
    Vec3 moment = Vec3::Zero();
    for (int a = 0; a < nodes; ++a) {
      Vec3 x = s.mesh.nodes[s.mesh.cell(0)[a]], f = Vec3::Zero();
      for (int k = 0; k < dim; ++k) {
        x[k] += 0.5 * (u_n[a * dim + k] + u_next[a * dim + k]);
        f[k] = out.force[a * dim + k];
      }
      moment += x.cross(f);
    }
    std::printf("mean dilatation %dD energy-momentum step: work %.12e, energy change %.12e, moment %.2e\n", dim, work,
                change, moment.norm());
    EXPECT_NEAR(work, change, 1e-12 * out.force.norm());
    EXPECT_LT(moment.norm(), 1e-12 * out.force.norm());
  }
}

TEST(MeanDilatation, AStepThatDoesNotMoveGivesTheStaticForce) {
  // u_n+1 = u_n: no discrete-gradient correction (dE = 0), and both step rules give the static
  // force at u_n.
  for (int dim : {2, 3}) {
    const FemSolid s = distorted_cell(dim);
    const std::vector<Real> u = random_displacement(s.mesh.nodes_per_cell() * dim, 0.1, 4);
    const ElementOutput still = at(s, dim, u, false);
    for (StepRule rule : {StepRule::midpoint, StepRule::energy_momentum}) {
      const ElementOutput out = step(s, dim, u, u, rule, false);
      EXPECT_LT((out.force - still.force).norm(), 1e-12 * still.force.norm());
      EXPECT_NEAR(out.energy, still.energy, 1e-12 * still.energy);
    }
  }
}

TEST(MeanDilatation, AHomogeneousDeformationGivesTheDisplacementElementsResult) {
  // u = (F - I) X with a constant F (stretch, shear and volume change): J is the same at every
  // point, so the mean dilatation is J and both elements give the same energy and force.
  for (int dim : {2, 3}) {
    FemSolid s = distorted_cell(dim);
    Mat3 F = Mat3::Identity();
    F << 1.1, 0.2, 0.05, -0.1, 0.95, 0.1, 0.02, 0.03, 1.02;
    if (dim == 2) F.row(2) = F.col(2) = Vec3(0, 0, 1);
    const int nodes = s.mesh.nodes_per_cell();
    std::vector<Real> u(nodes * dim);
    for (int a = 0; a < nodes; ++a) {
      const Vec3 x = (F - Mat3::Identity()) * s.mesh.nodes[s.mesh.cell(0)[a]];
      for (int k = 0; k < dim; ++k) u[a * dim + k] = x[k];
    }
    const ElementOutput mean = at(s, dim, u, false);
    s.volume = VolumeTreatment::pointwise;
    const ElementOutput pointwise = at(s, dim, u, false);
    EXPECT_NEAR(mean.energy, pointwise.energy, 1e-12 * pointwise.energy);
    EXPECT_LT((mean.force - pointwise.force).norm(), 1e-12 * pointwise.force.norm());
  }
}

TEST(MeanDilatation, OutputStressesUseTheCellsPressure) {
  // A 2 x 2 block whose cells are stretched differently: the mean-dilatation cell's Cauchy stress
  // is the rest of the energy's stress averaged over the cell plus the cell's pressure U'(theta)
  // on the diagonal; under a homogeneous deformation it equals the displacement element's. Both
  // to 1e-9 of the stress: round-off of a pressure lambda ln J with lambda = 5e3 mu, summed in
  // another order.
  FemModel model;
  model.dim = 2;
  FemSolid solid;
  solid.name = "block";
  solid.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(2, 2), {2, 2}, ElementType::quad4);
  solid.material.lame = {5e3, 1.0};
  solid.material.density = 1;
  solid.volume = VolumeTreatment::mean_dilatation;
  add_fem_solid(model, std::move(solid));
  finalize_fem_model(model);
  FemSolid& s = model.solids[0];
  VectorX u(model.dof_count());
  for (Index n = 0; n < s.mesh.node_count(); ++n) {
    const Vec3& X = s.mesh.nodes[n];
    u[model.dof(n, 0)] = 0.01 * X.x() + 0.02 * X.y();
    u[model.dof(n, 1)] = -0.015 * X.y();
  }
  std::vector<Real> mean, mean_vm, pointwise, pointwise_vm;
  cell_stresses(model, s, u, mean, mean_vm);
  s.volume = VolumeTreatment::pointwise;
  cell_stresses(model, s, u, pointwise, pointwise_vm);
  for (size_t i = 0; i < mean.size(); ++i) EXPECT_NEAR(mean[i], pointwise[i], 1e-9 * std::abs(pointwise[0]));
  // A non-homogeneous field: within a cell, J varies; the pressure part is U'(theta) for the cell.
  for (Index n = 0; n < s.mesh.node_count(); ++n) u[model.dof(n, 0)] += 0.01 * s.mesh.nodes[n].x() * s.mesh.nodes[n].y();
  s.volume = VolumeTreatment::mean_dilatation;
  cell_stresses(model, s, u, mean, mean_vm);
  const FemSolid& cell = model.solids[0];
  const Index* c = cell.mesh.cell(0);
  Real local[kMaxElementDofs];
  for (int a = 0; a < 4; ++a)
    for (int k = 0; k < 2; ++k) local[a * 2 + k] = u[model.dof(c[a], k)];
  const CellQuadrature q = cell.cell_quadrature(0);
  const HyperelasticMaterial rest = cell.material.without_volumetric_energy();
  Mat3 expected = Mat3::Zero();
  Real volume = 0, theta_minus_one = 0;
  for (int p = 0; p < q.points; ++p) {
    const Mat3 H = displacement_gradient(q.gradient + 4 * p, 4, 2, local);
    const Mat3 F = Mat3::Identity() + H;
    expected += q.weight[p] * F * rest.stress(green_lagrange_strain(H)) * F.transpose() / F.determinant();
    volume += q.weight[p];
    theta_minus_one += q.weight[p] * (F.determinant() - 1);
  }
  expected /= volume;
  expected.diagonal().array() += cell.material.volumetric_energy(theta_minus_one / volume).pressure;
  EXPECT_NEAR(mean[0], expected(0, 0), 1e-9 * expected.norm());
  EXPECT_NEAR(mean[1], expected(1, 1), 1e-9 * expected.norm());
  EXPECT_NEAR(mean[3], expected(0, 1), 1e-9 * expected.norm());
}

}  // namespace
}  // namespace moreau
