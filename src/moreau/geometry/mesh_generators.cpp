#include "moreau/geometry/mesh_generators.hpp"

#include <utility>

namespace moreau {

TriangleMesh make_grid_sheet(const Vec2& size, const std::array<int, 2>& resolution, const Vec3& center) {
  const int nx = resolution[0], nz = resolution[1];
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<size_t>(nx) * nz);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < nz; ++j)
      mesh.vertices.emplace_back(center.x() - 0.5 * size.x() + size.x() * i / (nx - 1), center.y(),
                                 center.z() - 0.5 * size.y() + size.y() * j / (nz - 1));
  auto id = [nz](int i, int j) { return static_cast<Index>(i * nz + j); };
  for (int i = 0; i + 1 < nx; ++i) {
    for (int j = 0; j + 1 < nz; ++j) {
      const Index p00 = id(i, j), p10 = id(i + 1, j), p01 = id(i, j + 1), p11 = id(i + 1, j + 1);
      // Counter-clockwise seen from +y: (p00, p01, p11) has normal (p01-p00)x(p11-p00) = +y.
      if ((i + j) % 2 == 0) {
        mesh.triangles.push_back({p00, p01, p11});
        mesh.triangles.push_back({p00, p11, p10});
      } else {
        mesh.triangles.push_back({p00, p01, p10});
        mesh.triangles.push_back({p10, p01, p11});
      }
    }
  }
  return mesh;
}

TetMesh make_box_tets(const Vec3& min, const Vec3& max, const std::array<int, 3>& cells) {
  const int nx = cells[0] + 1, ny = cells[1] + 1, nz = cells[2] + 1;
  TetMesh mesh;
  const Vec3 step = (max - min).cwiseQuotient(Vec3(cells[0], cells[1], cells[2]));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) mesh.vertices.push_back(min + Vec3(i * step.x(), j * step.y(), k * step.z()));
  auto id = [ny, nz](int i, int j, int k) { return static_cast<Index>((i * ny + j) * nz + k); };

  // The six paths from corner 000 to corner 111 along the cube's edges; each is one tetrahedron.
  static constexpr int kAxisOrder[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < cells[0]; ++i)
    for (int j = 0; j < cells[1]; ++j)
      for (int k = 0; k < cells[2]; ++k)
        for (const auto& order : kAxisOrder) {
          std::array<int, 3> c{i, j, k};
          std::array<Index, 4> tet{};
          tet[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            c[order[s]] += 1;
            tet[s + 1] = id(c[0], c[1], c[2]);
          }
          const auto& v = mesh.vertices;
          if (tet_signed_volume(v[tet[0]], v[tet[1]], v[tet[2]], v[tet[3]]) < 0) std::swap(tet[2], tet[3]);
          mesh.tets.push_back(tet);
        }
  return mesh;
}

}  // namespace moreau
