#pragma once
// Lagrange elements of the FEM engine: shape functions on the reference element and Gauss rules.
//   line2   xi in [-1, 1]                         N = (1 -+ xi)/2
//   tri3    area coordinates, xi, eta >= 0, xi + eta <= 1        N = (1 - xi - eta, xi, eta)
//   quad4   [-1, 1]^2, nodes counter-clockwise     N_a = (1 + xi_a xi)(1 + eta_a eta)/4
//   tet4    volume coordinates                     N = (1 - xi - eta - zeta, xi, eta, zeta)
//   hex8    [-1, 1]^3, bottom face (zeta = -1) counter-clockwise, then the top face
//           N_a = (1 + xi_a xi)(1 + eta_a eta)(1 + zeta_a zeta)/8
// (Hughes, The Finite Element Method, ch. 3.) Gauss rules: tensor-product Gauss-Legendre on
// line/quad/hex; symmetric rules on triangles (1 and 3 points) and tetrahedra (1 and 4 points).
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

enum class ElementType { line2, tri3, quad4, tet4, hex8 };

constexpr int kMaxElementNodes = 8;

/// Reference dimension (1, 2 or 3).
int element_dimension(ElementType type);
int element_node_count(ElementType type);
const char* element_name(ElementType type);
/// The element type of a facet (boundary edge or face) of `type`.
ElementType facet_type(ElementType type);
/// Local node lists of the facets of `type`, each ordered so that its normal (right-hand rule in
/// 3D; in 2D the edge runs with the element's counter-clockwise boundary) points out of the element.
const std::vector<std::vector<int>>& element_facets(ElementType type);

struct QuadraturePoint {
  Vec3 xi = Vec3::Zero();  // reference coordinates (unused components zero)
  Real weight = 0;
};

/// A Gauss rule exact for polynomials of `degree` on the reference element (degree <= 3).
std::vector<QuadraturePoint> gauss_rule(ElementType type, int degree);

/// Shape function values N[a] and reference derivatives dN[a] = dN_a/dxi (components past the
/// reference dimension zero) at xi.
void shape_functions(ElementType type, const Vec3& xi, Real* N, Vec3* dN);

}  // namespace moreau
