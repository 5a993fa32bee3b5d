#pragma once
// The pieces the solid elements (solid_element.cpp, mean_dilatation.cpp) share: the
// strain-displacement matrix, the tangent's material and geometric parts, and the output's
// bookkeeping. The formulas are in solid_element.hpp.
#include "moreau/fem/solids/solid_element.hpp"

namespace moreau {

using StrainMatrix = Eigen::Matrix<Real, 6, Eigen::Dynamic, 0, 6, kMaxElementDofs>;

/// B with dE_voigt = B du at deformation gradient F (engineering shears).
void strain_displacement(const Mat3& F, const Vec3* G, int nodes, int dim, StrainMatrix& B);

/// Adds scale (B^T CC B_right + geometric(S)) to K: the geometric part (G_a . S G_b) on the
/// diagonal of each node pair's block.
void add_tangent(const StrainMatrix& B, const StrainMatrix& B_right, const Mat6& CC, const Vec6& stress, const Vec3* G,
                 int nodes, int dim, Real scale, ElementMatrix& K);

/// Zeroes the output for n dofs (and its tangent, if asked).
void start_output(int n, bool with_tangent, ElementOutput& out);

/// Marks the cell inverted: not valid, infinite energy.
void mark_inverted(ElementOutput& out);

/// Gonzalez's discrete gradient at one point between the strains E0 and E1 (solid_element.hpp):
/// S_algo, and the tangent CC_algo with d S_algo = CC_algo dE1_engineering / 2 (the factor 1/2 of
/// d E_avg / d E1 kept outside, as for the midpoint rule's CC).
struct PointDiscreteGradient {
  Vec6 stress = Vec6::Zero();
  Mat6 tangent = Mat6::Zero();
  Real energy = 0;  // W(E1)
  bool valid = true;
};
PointDiscreteGradient discrete_gradient(const HyperelasticMaterial& material, const Mat3& E0, const Mat3& E1,
                                        bool with_tangent);

}  // namespace moreau
