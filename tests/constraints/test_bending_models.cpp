// The two cloth bending models against each other and against the continuum: a flat sheet
// rolled onto a cylinder of radius R has bending energy (k_B/2) A / R^2 (plate theory, one
// principal curvature 1/R).
#include <gtest/gtest.h>

#include <fstream>

#include "moreau/constraints/dihedral_bending.hpp"
#include "moreau/constraints/isometric_bending.hpp"
#include "moreau/errors.hpp"
#include "moreau/geometry/mesh_generators.hpp"
#include "moreau/solvers/xpbd/particle_projections.hpp"
#include "test_helpers.hpp"

using namespace moreau;

namespace {

struct SheetEnergies {
  Real dihedral, isometric, continuum;
};

enum class RollAxis { along_x, along_z, diagonal };

// A size x size sheet with n x n vertices rolled onto a cylinder of radius R (the arc running
// along x, z or the diagonal, isometrically); both discrete energies for bending stiffness k_B.
SheetEnergies rolled_sheet(int n, Real size, Real R, RollAxis axis, Real k_B) {
  const TriangleMesh sheet = make_grid_sheet(Vec2(size, size), {n, n}, Vec3::Zero());
  std::vector<Vec3> x = sheet.vertices;
  const Vec3 t = axis == RollAxis::along_x ? Vec3(1, 0, 0)
                 : axis == RollAxis::along_z ? Vec3(0, 0, 1)
                                             : Vec3(1, 0, 1).normalized();
  for (auto& p : x) {
    const Real u = p.dot(t);
    const Real along = R * std::sin(u / R), height = R * (1 - std::cos(u / R));
    p = p - u * t + along * t + Vec3(0, height, 0);
  }
  SheetEnergies e{0, 0, 0.5 * k_B * size * size / (R * R)};
  const auto& X = sheet.vertices;
  for (const Hinge& h : triangle_hinges(sheet.triangles)) {
    const Real theta = evaluate_dihedral(x[h.e0], x[h.e1], x[h.o0], x[h.o1]).theta;
    e.dihedral += 0.5 * theta * theta / hinge_compliance_from_bending_stiffness(X[h.e0], X[h.e1], X[h.o0], X[h.o1], k_B);
    IsometricBendingConstraints ib;
    ib.add(h, X[h.e0], X[h.e1], X[h.o0], X[h.o1],
           hinge_compliance_from_bending_stiffness(X[h.e0], X[h.e1], X[h.o0], X[h.o1], k_B), 0, 0);
    e.isometric += ib.energy(x.data(), -1);
  }
  return e;
}

}  // namespace

TEST(BendingModels, IsometricWeightsVanishOnTheRestPlaneAndMeasureTheAngle) {
  // A skewed flat hinge in a tilted plane.
  const Vec3 u = Vec3(1, 0.2, 0.1).normalized(), v = u.cross(Vec3(0.3, 1, -0.2)).normalized();
  const Vec3 E0 = Vec3(0.1, 0.2, 0.3), E1 = E0 + 0.8 * u, O0 = E0 + 0.3 * u + 0.5 * v, O1 = E0 + 0.6 * u - 0.35 * v;
  const auto K = isometric_hinge_weights(E0, E1, O0, O1);
  EXPECT_NEAR(K[0] + K[1] + K[2] + K[3], 0, 1e-14);
  std::vector<Vec3> x{E0, E1, O0, O1};
  IsometricHinge h{{0, 1, 2, 3}, K, 1, 0};
  EXPECT_LT(isometric_bending_value(h, x.data()).norm(), 1e-14);  // any planar placement: C = 0
  // Lifting o0 out of the plane: |C| = l theta + O(theta^3).
  const Vec3 normal = u.cross(v);
  x[2] += 1e-4 * normal;
  const Real theta = evaluate_dihedral(x[0], x[1], x[2], x[3]).theta, l = 0.8;
  EXPECT_NEAR(isometric_bending_value(h, x.data()).norm() / (l * std::abs(theta)), 1.0, 1e-6);
}

TEST(BendingModels, IsometricProjectionByHand) {
  // Unit square hinge: e0 = (0,0,0), e1 = (1,0,0), o0 = (0.5,0,1), o1 = (0.5,0,-1).
  // Hand computation: A_A = A_B = 1/2, l = 1, so K_o0 = K_o1 = l^2/(2A) = 1; a_0 = a_1 = 0.5 gives
  // K_e1 = -(0.5 + 0.5) = -1 and K_e0 = -(-1 + 1 + 1) = -1.
  std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, 1), Vec3(0.5, 0, -1)};
  const auto K = isometric_hinge_weights(x[0], x[1], x[2], x[3]);
  EXPECT_NEAR(K[0], -1, 1e-15);
  EXPECT_NEAR(K[1], -1, 1e-15);
  EXPECT_NEAR(K[2], 1, 1e-15);
  EXPECT_NEAR(K[3], 1, 1e-15);
  // Lift o0 by 0.1 and let only o0 move (w = 2 /kg), per-angle compliance 0.04 /(N m), so with
  // l = 1 the hinge compliance is alpha = l^2 0.04 = 0.04 m/N; h = 0.1 s:
  // C = (0, 0.1, 0), alpha~ = 0.04/0.01 = 4, dlambda = -C / (w K_o0^2 + alpha~) = -(0, 0.1, 0)/6,
  // dx_o0 = w K_o0 dlambda = (0, -1/30, 0), so o0 ends at y = 0.1 - 1/30 = 1/15.
  IsometricBendingConstraints c;
  c.add({0, 1, 2, 3}, x[0], x[1], x[2], x[3], 0.04, 0, 0);
  std::vector<Real> inv_mass{0, 0, 2, 0};
  c.color(inv_mass);
  x[2].y() = 0.1;
  const std::vector<Vec3> start = x;
  std::vector<Vec3> lambda(1, Vec3::Zero());
  xpbd_project(c, lambda.data(), SubstepContext{x.data(), start.data(), inv_mass.data(), 0.1});
  EXPECT_NEAR(x[2].y(), 1.0 / 15, 1e-15);
  EXPECT_NEAR(lambda[0].y(), -0.1 / 6, 1e-15);
  EXPECT_EQ(x[0], start[0]);
}

// Rolling about a mesh-edge direction puts the whole bend in one edge family; every hinge row
// except the two half-strips at the sheet's edges carries it, so the discrete energy covers
// (n-2)/(n-1) of the area. Both models must then give (k_B/2) A_covered / R^2 within 0.2 %
// (the isometric model differs from the exact angle by O(theta^2) = O((a/R)^2) ~ 1e-4).
TEST(BendingModels, SheetRolledOntoCylinderHasPlateEnergy) {
  for (int n : {21, 41}) {
    const SheetEnergies e = rolled_sheet(n, 1.0, 2.0, RollAxis::along_x, 3e-3);
    const Real covered = e.continuum * (n - 2.0) / (n - 1.0);
    EXPECT_NEAR(e.dihedral / covered, 1.0, 2e-3) << n;
    EXPECT_NEAR(e.isometric / covered, 1.0, 2e-3) << n;
    const SheetEnergies ez = rolled_sheet(n, 1.0, 2.0, RollAxis::along_z, 3e-3);
    EXPECT_NEAR(ez.dihedral / covered, 1.0, 2e-3) << n;
  }
  // Rolling about a diagonal bends every hinge: hinge bending on this grid is 1.5x stiffer there
  // (a property of the discrete model, documented in docs/validation.md). Measured 1.494 at 81
  // vertices; 0.03 covers the missing boundary hinges (~1/80 of the sheet).
  const SheetEnergies d = rolled_sheet(81, 1.0, 2.0, RollAxis::diagonal, 3e-3);
  EXPECT_NEAR(d.dihedral / d.continuum, 1.5, 0.03);
  EXPECT_NEAR(d.isometric / d.dihedral, 1.0, 1e-3);
}

TEST(BendingModels, IsometricBendingRejectsACurvedRestShape) {
  const std::string obj = test::temp_dir("folded") + "/folded.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0.5 0 1\nv 0.5 1 0\nf 1 2 3\nf 2 1 4\n";  // a 90-degree fold
  try {
    test::scene_from_json(fmt::format(R"({{"name": "fold", "objects": [{{"name": "sheet", "kind": "cloth",
      "mesh": {{"type": "obj", "file": "{}"}},
      "material": {{"area_density": 0.1, "bending_stiffness": 1e-4, "bending_model": "isometric"}}}}]}})", obj));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("objects[0].material.bending_model"), std::string::npos) << what;
    EXPECT_NE(what.find("flat rest shape"), std::string::npos) << what;
  }
}
