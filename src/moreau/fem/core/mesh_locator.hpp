#pragma once
// Finding the cell of a quad4/hex8 mesh that contains a point, and the point's reference
// coordinates there: the isoparametric map x(xi) = sum_a N_a(xi) X_a is inverted by Newton's
// method in each candidate cell. Candidates come from a uniform grid of buckets over the mesh's
// bounding box, each bucket listing the cells whose bounding boxes overlap it (about one cell per
// bucket), so a query costs a few inversions whatever the mesh size.
// Used to sample a flow at a point and to map an immersed solid's nodes into the fluid mesh.
#include <optional>
#include <vector>

#include "moreau/fem/core/fem_mesh.hpp"

namespace moreau {

/// A point inside a cell: the cell, its reference coordinates and the cell's shape functions and
/// their gradients in x there.
struct MeshPoint {
  Index cell = -1;
  Vec3 xi = Vec3::Zero();
  Real shape[kMaxElementNodes] = {};
  Vec3 gradient[kMaxElementNodes] = {};  // grad_x N_a = J^-T grad_xi N_a (J = dx/dxi); 0 beyond the mesh's dimension
};

class MeshLocator {
 public:
  /// Keeps a reference to `mesh` (quad4 or hex8), which must outlive the locator.
  explicit MeshLocator(const FemMesh& mesh);

  /// The cell containing `point` (on a shared face, the first in cell order), or nothing if the
  /// point is outside the mesh. Points within 1e-9 of a cell's reference extent count as inside.
  /// `hint`: a cell to try first (where the point was a moment ago), or -1.
  std::optional<MeshPoint> locate(const Vec3& point, Index hint = -1) const;

 private:
  bool inside_cell(Index e, const Vec3& point, MeshPoint& found) const;

  const FemMesh& mesh_;
  Vec3 lo_ = Vec3::Zero(), bucket_size_ = Vec3::Ones();
  std::array<int, 3> buckets_ = {1, 1, 1};
  std::vector<Index> bucket_start_, bucket_cells_;  // CSR: cells of bucket b in [start[b], start[b+1])
};

}  // namespace moreau
