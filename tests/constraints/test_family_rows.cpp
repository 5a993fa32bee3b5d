// Every particle constraint family in ParticleFamilies, through the row interface that solvers
// use: the gradient blocks are the derivatives of C, the energy is the one the rows' compliance
// defines, and the family's closed-form XPBD kernel takes the same step as the generic projection
// of its rows. A family added to the list without a sample below does not compile.
#include <gtest/gtest.h>

#include <random>

#include "moreau/constraints/particle_families.hpp"
#include "moreau/solvers/xpbd/particle_projections.hpp"

using namespace moreau;

namespace {

// Five rest points in the plane z = 0 (for surface families, which need a flat rest shape for
// isometric bending) or spanning two positively oriented tetrahedra (for volume families).
std::vector<Vec3> flat_rest() {
  return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.4, 0.9, 0), Vec3(0.6, -0.8, 0), Vec3(1.3, 0.7, 0)};
}
std::vector<Vec3> solid_rest() { return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)}; }

// Each sample has two or more constraints sharing particles (so colouring matters), non-zero
// compliance and damping on some of them, and a hard one where the family allows it.
template <class Family>
struct Sample;

template <>
struct Sample<DistanceConstraints> {
  static std::vector<Vec3> build(DistanceConstraints& c) {
    const auto X = flat_rest();
    for (auto [a, b] : std::vector<std::array<Index, 2>>{{0, 1}, {1, 2}, {0, 2}, {2, 4}})
      c.add(a, b, (X[a] - X[b]).norm(), a == 0 ? 1e-3 : 0.0, 0.01, 0);
    return X;
  }
};
template <>
struct Sample<DihedralBendingConstraints> {
  static std::vector<Vec3> build(DihedralBendingConstraints& c) {
    const auto X = flat_rest();
    c.add({0, 1, 2, 3}, 0.0, 1e-2, 0.01, 0);
    c.add({1, 2, 0, 4}, 0.0, 0.0, 0.0, 0);
    return X;
  }
};
template <>
struct Sample<IsometricBendingConstraints> {
  static std::vector<Vec3> build(IsometricBendingConstraints& c) {
    const auto X = flat_rest();
    c.add({0, 1, 2, 3}, X[0], X[1], X[2], X[3], 1e-2, 0.01, 0);
    c.add({1, 2, 0, 4}, X[1], X[2], X[0], X[4], 5e-3, 0.0, 0);
    return X;
  }
};
template <>
struct Sample<TriangleStrainConstraints> {
  static std::vector<Vec3> build(TriangleStrainConstraints& c) {
    const auto X = flat_rest();
    c.add({0, 1, 2}, X[0], X[1], X[2], 1e3, 0.3, 0.01, 0.01, 0);
    c.add({1, 4, 2}, X[1], X[4], X[2], 2e3, 0.0, 0.02, 0.0, 0);
    return X;
  }
};
template <>
struct Sample<NeoHookeanTetConstraints> {
  static std::vector<Vec3> build(NeoHookeanTetConstraints& c) {
    const auto X = solid_rest();
    c.add({0, 1, 2, 3}, {X[0], X[1], X[2], X[3]}, 1e4, 0.3, 0.01, 0);
    c.add({1, 4, 2, 3}, {X[1], X[4], X[2], X[3]}, 3e4, 0.45, 0.0, 0);
    return X;
  }
};
template <>
struct Sample<GreenStrainTetConstraints> {
  static std::vector<Vec3> build(GreenStrainTetConstraints& c) {
    const auto X = solid_rest();
    c.add({0, 1, 2, 3}, {X[0], X[1], X[2], X[3]}, 1e4, 0.3, 0.01, 0);
    c.add({1, 4, 2, 3}, {X[1], X[4], X[2], X[3]}, 3e4, 0.0, 0.0, 0);
    return X;
  }
};
template <>
struct Sample<TetVolumeConstraints> {
  static std::vector<Vec3> build(TetVolumeConstraints& c) {
    const auto X = solid_rest();
    c.add({0, 1, 2, 3}, {X[0], X[1], X[2], X[3]}, 1e-4, 0.01, 0);
    c.add({1, 4, 2, 3}, {X[1], X[4], X[2], X[3]}, 0.0, 0.0, 0);
    return X;
  }
};
template <>
struct Sample<AttachmentConstraints> {
  static std::vector<Vec3> build(AttachmentConstraints& c) {
    const auto X = solid_rest();
    c.add(0, X[0], 1e-3, 0.01, 0);
    c.add(2, X[2], 0.0, 0.0, 0);
    c.add(4, X[4], 2e-3, 0.0, 0);
    return X;
  }
};

template <class Tuple>
struct AsTestTypes;
template <class... F>
struct AsTestTypes<std::tuple<F...>> {
  using type = ::testing::Types<F...>;
};

// A family instance with rest points X, a deformed configuration x (about 5 % of the size), a
// substep start, inverse masses (one particle fixed) and multipliers from earlier iterations.
template <class Family>
struct Setup {
  Family family;
  std::vector<Vec3> rest, x, start;
  std::vector<Real> inv_mass{1.0, 0.5, 2.0, 0.0, 1.5};
  std::vector<typename Family::Multiplier> lambda;

  Setup() {
    rest = Sample<Family>::build(family);
    family.color(inv_mass);
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(-1, 1);
    for (const Vec3& X : rest) {
      x.push_back(X + 0.05 * Vec3(u(rng), u(rng), u(rng)));
      start.push_back(X + 0.03 * Vec3(u(rng), u(rng), u(rng)));
    }
    for (size_t k = 0; k < family.size(); ++k) {
      lambda.push_back(zero_multiplier<typename Family::Multiplier>());
      for (int r = 0; r < Family::Rows::kRows; ++r) multiplier_rows<Family>(lambda.back())(r) = 1e-4 * u(rng);
    }
  }
};

template <class Family>
class FamilyRows : public ::testing::Test {};
TYPED_TEST_SUITE(FamilyRows, AsTestTypes<ParticleFamilies>::type);

// Central differences with step 1e-6 m: truncation O(1e-12 C''') plus round-off O(1e-16 / 1e-6),
// so 1e-6 relative to the largest gradient entry is a wide but meaningful bound.
TYPED_TEST(FamilyRows, GradientBlocksAreTheDerivativesOfC) {
  Setup<TypeParam> s;
  constexpr Real step = 1e-6;
  for (Index k = 0; k < static_cast<Index>(s.family.size()); ++k) {
    const auto rows = s.family.rows(k, s.x.data());
    Real scale = 1;
    for (const auto& g : rows.gradient) scale = std::max(scale, g.cwiseAbs().maxCoeff());
    for (int i = 0; i < TypeParam::Rows::kParticles; ++i)
      for (int d = 0; d < 3; ++d) {
        std::vector<Vec3> plus = s.x, minus = s.x;
        plus[rows.particle[i]][d] += step;
        minus[rows.particle[i]][d] -= step;
        const typename TypeParam::Rows::Vector difference =
            (s.family.rows(k, plus.data()).C - s.family.rows(k, minus.data()).C) / (2 * step);
        EXPECT_LT((difference - rows.gradient[i].col(d)).norm(), 1e-6 * scale)
            << TypeParam::kName << " constraint " << k << ", particle " << i << ", axis " << d;
      }
  }
}

// energy() must be the energy of the rows' compliance, 0.5 C^T alpha^-1 C over compliant
// constraints, measured from the rest configuration (where every family's energy is zero).
// The two sums differ only in the order of operations and in solving with alpha instead of a
// closed-form inverse (triangle strain), so 1e-9 of the energies involved is round-off with a
// wide margin; a wrong compliance or a missing row changes them by O(1).
TYPED_TEST(FamilyRows, EnergyIsTheEnergyOfTheRowsCompliance) {
  Setup<TypeParam> s;
  auto row_energy = [&](const std::vector<Vec3>& x) {
    Real e = 0;
    for (Index k = 0; k < static_cast<Index>(s.family.size()); ++k) {
      const auto rows = s.family.rows(k, x.data());
      if (rows.compliance.isZero()) continue;
      e += 0.5 * rows.C.dot(rows.compliance.ldlt().solve(rows.C));
    }
    return e;
  };
  EXPECT_NEAR(s.family.energy(s.rest.data(), -1), 0.0, 1e-9 * row_energy(s.rest) + 1e-12) << TypeParam::kName;
  const Real expected = row_energy(s.x) - row_energy(s.rest);
  ASSERT_GT(expected, 0) << TypeParam::kName << ": the deformed sample stores no energy";
  EXPECT_NEAR(s.family.energy(s.x.data(), -1), expected, 1e-9 * (expected + row_energy(s.rest)))
      << TypeParam::kName;
}

// One sweep by the family's closed-form kernel (particle_projections.hpp) and one by the generic
// row projection, from the same state, with damping and earlier multipliers: the same positions
// and multipliers up to round-off (1e-12 relative; they solve the same small linear system).
TYPED_TEST(FamilyRows, ClosedFormKernelTakesTheGenericRowStep) {
  Setup<TypeParam> closed, generic;
  const std::vector<Vec3> before = closed.x;
  const Real h = 1e-2;
  xpbd_project(closed.family, closed.lambda.data(),
               SubstepContext{closed.x.data(), closed.start.data(), closed.inv_mass.data(), h});
  const SubstepContext ctx{generic.x.data(), generic.start.data(), generic.inv_mass.data(), h};
  for_each_by_color(generic.family.batches,
                    [&](Index k) { xpbd_project_rows(generic.family, k, generic.lambda[k], ctx); });
  Real moved = 0;
  for (size_t p = 0; p < closed.x.size(); ++p) {
    EXPECT_LT((closed.x[p] - generic.x[p]).norm(), 1e-12 * (1 + closed.x[p].norm())) << TypeParam::kName << " particle " << p;
    moved = std::max(moved, (closed.x[p] - before[p]).norm());
  }
  EXPECT_GT(moved, 1e-4) << TypeParam::kName << ": the sweep did not move the sample";
  for (size_t k = 0; k < closed.lambda.size(); ++k) {
    const auto a = multiplier_rows<TypeParam>(closed.lambda[k]), b = multiplier_rows<TypeParam>(generic.lambda[k]);
    EXPECT_LT((a - b).norm(), 1e-10 * (1 + a.norm())) << TypeParam::kName << " constraint " << k;
  }
}

}  // namespace
