#include "moreau/fem/core/elements.hpp"

#include <cmath>
#include <stdexcept>

namespace moreau {

int element_dimension(ElementType type) {
  switch (type) {
    case ElementType::line2: return 1;
    case ElementType::tri3:
    case ElementType::quad4: return 2;
    case ElementType::tet4:
    case ElementType::hex8: return 3;
  }
  return 0;
}

int element_node_count(ElementType type) {
  switch (type) {
    case ElementType::line2: return 2;
    case ElementType::tri3: return 3;
    case ElementType::quad4: return 4;
    case ElementType::tet4: return 4;
    case ElementType::hex8: return 8;
  }
  return 0;
}

const char* element_name(ElementType type) {
  static const char* names[] = {"line2", "tri3", "quad4", "tet4", "hex8"};
  return names[static_cast<int>(type)];
}

ElementType facet_type(ElementType type) {
  switch (type) {
    case ElementType::tri3:
    case ElementType::quad4: return ElementType::line2;
    case ElementType::tet4: return ElementType::tri3;
    case ElementType::hex8: return ElementType::quad4;
    case ElementType::line2: break;
  }
  throw std::logic_error("a line element has no facets");
}

const std::vector<std::vector<int>>& element_facets(ElementType type) {
  static const std::vector<std::vector<int>> tri = {{0, 1}, {1, 2}, {2, 0}};
  static const std::vector<std::vector<int>> quad = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  // Outward by the right-hand rule for a positively oriented tetrahedron (0, 1, 2, 3).
  static const std::vector<std::vector<int>> tet = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  static const std::vector<std::vector<int>> hex = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const std::vector<std::vector<int>> none;
  switch (type) {
    case ElementType::tri3: return tri;
    case ElementType::quad4: return quad;
    case ElementType::tet4: return tet;
    case ElementType::hex8: return hex;
    case ElementType::line2: break;
  }
  return none;
}

namespace {

// Gauss-Legendre points and weights on [-1, 1] with n = 1 or 2 points (exact to degree 2n - 1).
std::vector<std::pair<Real, Real>> gauss_legendre(int degree) {
  if (degree <= 1) return {{0.0, 2.0}};
  const Real g = 1 / std::sqrt(3.0);
  return {{-g, 1.0}, {g, 1.0}};
}

}  // namespace

std::vector<QuadraturePoint> gauss_rule(ElementType type, int degree) {
  if (degree > 3) throw std::logic_error("Gauss rules are provided up to degree 3");
  std::vector<QuadraturePoint> rule;
  const auto line = gauss_legendre(degree);
  switch (type) {
    case ElementType::line2:
      for (const auto& [x, w] : line) rule.push_back({Vec3(x, 0, 0), w});
      break;
    case ElementType::quad4:
      for (const auto& [y, wy] : line)
        for (const auto& [x, wx] : line) rule.push_back({Vec3(x, y, 0), wx * wy});
      break;
    case ElementType::hex8:
      for (const auto& [z, wz] : line)
        for (const auto& [y, wy] : line)
          for (const auto& [x, wx] : line) rule.push_back({Vec3(x, y, z), wx * wy * wz});
      break;
    case ElementType::tri3:
      if (degree <= 1) {
        rule.push_back({Vec3(1.0 / 3, 1.0 / 3, 0), 0.5});
      } else if (degree == 2) {
        // Degree 2 (Strang & Fix): (1/6, 1/6), (2/3, 1/6), (1/6, 2/3), weight 1/6 each.
        for (const Vec3& p : {Vec3(1.0 / 6, 1.0 / 6, 0), Vec3(2.0 / 3, 1.0 / 6, 0), Vec3(1.0 / 6, 2.0 / 3, 0)})
          rule.push_back({p, 1.0 / 6});
      } else {
        // Degree 3 by Dunavant's 6-point rule (exact to degree 4, all weights positive).
        const Real a = 0.445948490915965, b = 0.091576213509771;
        const Real wa = 0.223381589678011 / 2, wb = 0.109951743655322 / 2;
        for (const Vec3& p : {Vec3(a, a, 0), Vec3(1 - 2 * a, a, 0), Vec3(a, 1 - 2 * a, 0)}) rule.push_back({p, wa});
        for (const Vec3& p : {Vec3(b, b, 0), Vec3(1 - 2 * b, b, 0), Vec3(b, 1 - 2 * b, 0)}) rule.push_back({p, wb});
      }
      break;
    case ElementType::tet4:
      if (degree <= 1) {
        rule.push_back({Vec3::Constant(0.25), 1.0 / 6});
      } else {
        // Degree 2 (Keast): a = (5 - sqrt 5)/20, b = (5 + 3 sqrt 5)/20, weight 1/24 each.
        const Real a = (5 - std::sqrt(5.0)) / 20, b = (5 + 3 * std::sqrt(5.0)) / 20;
        for (const Vec3& p : {Vec3(a, a, a), Vec3(b, a, a), Vec3(a, b, a), Vec3(a, a, b)}) rule.push_back({p, 1.0 / 24});
        if (degree == 3) throw std::logic_error("tetrahedra have Gauss rules up to degree 2");
      }
      break;
  }
  return rule;
}

void shape_functions(ElementType type, const Vec3& xi, Real* N, Vec3* dN) {
  const Real x = xi.x(), y = xi.y(), z = xi.z();
  switch (type) {
    case ElementType::line2:
      N[0] = 0.5 * (1 - x);
      N[1] = 0.5 * (1 + x);
      dN[0] = Vec3(-0.5, 0, 0);
      dN[1] = Vec3(0.5, 0, 0);
      return;
    case ElementType::tri3:
      N[0] = 1 - x - y;
      N[1] = x;
      N[2] = y;
      dN[0] = Vec3(-1, -1, 0);
      dN[1] = Vec3(1, 0, 0);
      dN[2] = Vec3(0, 1, 0);
      return;
    case ElementType::quad4: {
      static const Real sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
      for (int a = 0; a < 4; ++a) {
        N[a] = 0.25 * (1 + sx[a] * x) * (1 + sy[a] * y);
        dN[a] = Vec3(0.25 * sx[a] * (1 + sy[a] * y), 0.25 * sy[a] * (1 + sx[a] * x), 0);
      }
      return;
    }
    case ElementType::tet4:
      N[0] = 1 - x - y - z;
      N[1] = x;
      N[2] = y;
      N[3] = z;
      dN[0] = Vec3(-1, -1, -1);
      dN[1] = Vec3(1, 0, 0);
      dN[2] = Vec3(0, 1, 0);
      dN[3] = Vec3(0, 0, 1);
      return;
    case ElementType::hex8: {
      static const Real sx[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, sy[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
                        sz[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
      for (int a = 0; a < 8; ++a) {
        const Real fx = 1 + sx[a] * x, fy = 1 + sy[a] * y, fz = 1 + sz[a] * z;
        N[a] = 0.125 * fx * fy * fz;
        dN[a] = 0.125 * Vec3(sx[a] * fy * fz, sy[a] * fx * fz, sz[a] * fx * fy);
      }
      return;
    }
  }
}

}  // namespace moreau
