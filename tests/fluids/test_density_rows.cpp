// The fluid density constraint's evaluation (fluids/density_constraint.hpp), which every solver
// reads: grad_{x_i} C_i and the gradients of the neighbours it moves are the derivatives of C_i,
// they sum to zero away from walls (C_i depends on differences of positions only), and the
// weighted squared gradients are the off-i diagonal of J W J^T.
#include <gtest/gtest.h>

#include <random>

#include "moreau/fluids/density_constraint.hpp"
#include "moreau/fluids/fluid_neighbors.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

TEST(DensityRows, GradientsAreTheDerivativesOfTheConstraintAndSumToZero) {
  // A weightless block of water (r = 1 cm) with every particle moved by up to 1 mm, so that no
  // gradient vanishes by the lattice's symmetry; the particle nearest the centre has only fluid
  // neighbours.
  Scene scene = test::scene_from_json(R"({"name": "rows", "settings": {"gravity": [0, 0, 0]},
    "objects": [{"name": "water", "kind": "fluid", "particle_radius": 0.01,
                 "block": {"min": [-0.1, -0.1, -0.1], "max": [0.1, 0.1, 0.1]}}]})");
  const FluidModel& fm = scene.model.fluid;
  FluidState& f = scene.state.fluid;
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> jitter(-0.001, 0.001);
  for (Index i = 0; i < f.count; ++i) f.position[i] += Vec3(jitter(rng), jitter(rng), jitter(rng));
  FluidScratch scratch;
  scratch.fit(fm);
#pragma omp parallel num_threads(1)
  update_fluid_neighbors(scene.model, f, scratch, 0);
  Index i = 0;
  for (Index k = 0; k < f.count; ++k)
    if (f.position[k].norm() < f.position[i].norm()) i = k;

  const DensityEvaluation e = evaluate_density_constraint(fm, f, nullptr, i);
  EXPECT_TRUE(e.boundary_gradient.isZero());
  EXPECT_EQ(e.solid_weight, 0);
  std::vector<std::pair<Index, Vec3>> neighbours;
  Vec3 sum = e.gradient;
  Real weight = 0, magnitude = e.gradient.norm();
  for_each_density_gradient(fm, f, i, [&](DensityNeighbor kind, Index j, const Vec3& g) {
    EXPECT_EQ(kind, DensityNeighbor::fluid);
    neighbours.emplace_back(j, g);
    sum += g;
    magnitude += g.norm();
    weight += f.inv_mass[j] * g.squaredNorm();
  });
  ASSERT_GT(neighbours.size(), 20u);
  // The evaluation uses the solver's branch-free kernel, whose floor on r changes values by
  // < 1e-11 relative to the reference kernel the visitor uses (SphKernel.SolverChunksMatch...):
  // 1e-10 of the summed magnitudes holds that and fails any missing or wrongly signed term.
  EXPECT_LT(sum.norm(), 1e-10 * magnitude);
  const Real V = fm.particle_volume;
  EXPECT_NEAR(weight, V * V * e.fluid_kernel_weight, 1e-10 * weight);

  // Central differences with step 1e-7 m: truncation ~ eps^2 |C'''| ~ 1e-14 * 1e4 = 1e-10 1/m,
  // round-off ~ 1e-16 / 1e-7 = 1e-9 1/m; 1e-6 1/m is far above both and far below the gradients.
  const Real eps = 1e-7;
  auto derivative = [&](Index moved, int axis) {
    const Vec3 keep = f.position[moved];
    f.position[moved](axis) = keep(axis) + eps;
    const Real plus = evaluate_density_constraint(fm, f, nullptr, i).C;
    f.position[moved](axis) = keep(axis) - eps;
    const Real minus = evaluate_density_constraint(fm, f, nullptr, i).C;
    f.position[moved] = keep;
    return (plus - minus) / (2 * eps);
  };
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(derivative(i, axis), e.gradient(axis), 1e-6);
  for (size_t k = 0; k < neighbours.size(); k += 5)
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_NEAR(derivative(neighbours[k].first, axis), neighbours[k].second(axis), 1e-6)
          << "neighbour " << neighbours[k].first << " axis " << axis;
}

}  // namespace
}  // namespace moreau
