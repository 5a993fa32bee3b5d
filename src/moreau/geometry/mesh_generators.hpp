#pragma once
// Structured mesh generators for scene files: a horizontal cloth sheet and a box of tetrahedra.
#include "moreau/geometry/meshes.hpp"

namespace moreau {

/// A horizontal sheet in the xz plane at height center.y, size[0] along x and size[1] along z,
/// with resolution[0] x resolution[1] vertices. Diagonals alternate so that the triangulation
/// has no preferred shear direction. Normals point to +y.
TriangleMesh make_grid_sheet(const Vec2& size, const std::array<int, 2>& resolution, const Vec3& center);

/// How a box cell is cut into tetrahedra.
enum class CellSplit {
  six,   // six tetrahedra around the cell's main diagonal (Freudenthal/Kuhn); uniform, symmetric
  five,  // one central tetrahedron and four corner ones, mirrored in alternate cells to conform
};

/// An axis-aligned box [min, max] split into cells[0] x cells[1] x cells[2] cells, each cut into
/// tetrahedra as `split` says; both splits conform across cell faces.
TetMesh make_box_tets(const Vec3& min, const Vec3& max, const std::array<int, 3>& cells,
                      CellSplit split = CellSplit::six);

}  // namespace moreau
