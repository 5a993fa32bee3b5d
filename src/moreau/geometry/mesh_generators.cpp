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

namespace {

// Corners of a cell as bit patterns (x, y, z) -> x + 2y + 4z.
constexpr int corner(int x, int y, int z) { return x + 2 * y + 4 * z; }

// Six tetrahedra: the six monotone edge paths from corner 000 to 111.
constexpr int kSixSplit[6][4] = {
    {corner(0, 0, 0), corner(1, 0, 0), corner(1, 1, 0), corner(1, 1, 1)},
    {corner(0, 0, 0), corner(1, 0, 0), corner(1, 0, 1), corner(1, 1, 1)},
    {corner(0, 0, 0), corner(0, 1, 0), corner(1, 1, 0), corner(1, 1, 1)},
    {corner(0, 0, 0), corner(0, 1, 0), corner(0, 1, 1), corner(1, 1, 1)},
    {corner(0, 0, 0), corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1)},
    {corner(0, 0, 0), corner(0, 0, 1), corner(0, 1, 1), corner(1, 1, 1)}};

// Five tetrahedra for an "even" cell: the central tetrahedron on the corners with an even number
// of set bits {000, 110, 101, 011}, and one tetrahedron cutting off each remaining corner. An odd
// cell uses the mirror image (x -> 1 - x), so every face diagonal matches its neighbour's.
constexpr int kFiveSplitEven[5][4] = {
    {corner(0, 0, 0), corner(1, 1, 0), corner(1, 0, 1), corner(0, 1, 1)},
    {corner(1, 0, 0), corner(0, 0, 0), corner(1, 1, 0), corner(1, 0, 1)},
    {corner(0, 1, 0), corner(0, 0, 0), corner(1, 1, 0), corner(0, 1, 1)},
    {corner(0, 0, 1), corner(0, 0, 0), corner(1, 0, 1), corner(0, 1, 1)},
    {corner(1, 1, 1), corner(1, 1, 0), corner(1, 0, 1), corner(0, 1, 1)}};

}  // namespace

TetMesh make_box_tets(const Vec3& min, const Vec3& max, const std::array<int, 3>& cells, CellSplit split) {
  const int nx = cells[0] + 1, ny = cells[1] + 1, nz = cells[2] + 1;
  TetMesh mesh;
  const Vec3 step = (max - min).cwiseQuotient(Vec3(cells[0], cells[1], cells[2]));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) mesh.vertices.push_back(min + Vec3(i * step.x(), j * step.y(), k * step.z()));
  auto id = [ny, nz](int i, int j, int k) { return static_cast<Index>((i * ny + j) * nz + k); };

  auto add = [&](int i, int j, int k, const int (&corners)[4], bool mirror_x) {
    std::array<Index, 4> tet{};
    for (int c = 0; c < 4; ++c) {
      const int x = corners[c] & 1, y = (corners[c] >> 1) & 1, z = (corners[c] >> 2) & 1;
      tet[c] = id(i + (mirror_x ? 1 - x : x), j + y, k + z);
    }
    const auto& v = mesh.vertices;
    if (tet_signed_volume(v[tet[0]], v[tet[1]], v[tet[2]], v[tet[3]]) < 0) std::swap(tet[2], tet[3]);
    mesh.tets.push_back(tet);
  };
  for (int i = 0; i < cells[0]; ++i)
    for (int j = 0; j < cells[1]; ++j)
      for (int k = 0; k < cells[2]; ++k) {
        if (split == CellSplit::six) {
          for (const auto& t : kSixSplit) add(i, j, k, t, false);
        } else {
          const bool odd = (i + j + k) % 2 != 0;
          for (const auto& t : kFiveSplitEven) add(i, j, k, t, odd);
        }
      }
  return mesh;
}

}  // namespace moreau
