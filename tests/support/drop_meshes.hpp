#pragma once
// OBJ surfaces for a spherical drop inside a box of liquid, filled on one particle lattice: the
// drop's sphere, and the liquid's box with the same sphere as a second shell, so the ray-parity
// fill leaves the hole that the drop fills. The sphere's bounding box must lie a whole number of
// spacings from the box's for the two lattices to meet.
#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "moreau/math/types.hpp"

namespace moreau::test {

/// The sphere of `radius` about `center`, from an octahedron whose faces are split in four four
/// times: its vertices include the six axis points, so its bounding box is exact. Vertices are
/// numbered from `first_vertex` (OBJ counts from 1); there are 1,026 of them.
inline void write_sphere_shell(std::ofstream& out, int first_vertex, Real radius, const Vec3& center) {
  std::vector<Vec3> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<std::array<int, 3>> faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < 4; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, added] = midpoint.try_emplace(key, static_cast<int>(v.size()));
      if (added) v.push_back((v[a] + v[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> split;
    for (const auto& [a, b, c] : faces) {
      const int ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
      split.insert(split.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    faces = split;
  }
  for (const Vec3& p : v) out << fmt::format("v {:.9f} {:.9f} {:.9f}\n", center.x() + radius * p.x(),
                                            center.y() + radius * p.y(), center.z() + radius * p.z());
  for (const auto& [a, b, c] : faces) out << fmt::format("f {} {} {}\n", first_vertex + a, first_vertex + b, first_vertex + c);
}

/// drop.obj (the sphere) and surround.obj (the liquid's box |x|, |z| <= half_width, 0 <= y <=
/// height, with the sphere as a second shell) in `dir`.
inline void write_drop_meshes(const std::string& dir, Real half_width, Real height, Real drop_radius,
                              const Vec3& drop_center) {
  std::ofstream drop(dir + "/drop.obj");
  write_sphere_shell(drop, 1, drop_radius, drop_center);
  std::ofstream surround(dir + "/surround.obj");
  for (int i = 0; i < 8; ++i)
    surround << fmt::format("v {} {} {}\n", (i & 1) ? half_width : -half_width, (i & 2) ? height : 0.0,
                            (i & 4) ? half_width : -half_width);
  // Vertex i + 1 sits at the corner (i & 1, i & 2, i & 4); two triangles per face.
  surround << "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  write_sphere_shell(surround, 9, drop_radius, drop_center);
}

}  // namespace moreau::test
