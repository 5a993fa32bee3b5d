#include "moreau/fem/core/mesh_locator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace moreau {

namespace {

struct Bounds {
  Vec3 lo, hi;
};

Bounds cell_bounds(const FemMesh& mesh, Index e) {
  const Index* c = mesh.cell(e);
  Bounds b{mesh.nodes[c[0]], mesh.nodes[c[0]]};
  for (int a = 1; a < mesh.nodes_per_cell(); ++a) {
    b.lo = b.lo.cwiseMin(mesh.nodes[c[a]]);
    b.hi = b.hi.cwiseMax(mesh.nodes[c[a]]);
  }
  return b;
}

}  // namespace

MeshLocator::MeshLocator(const FemMesh& mesh) : mesh_(mesh) {
  if (mesh.element != ElementType::quad4 && mesh.element != ElementType::hex8)
    throw std::logic_error(fmt::format("MeshLocator: quad4 or hex8 cells, not {}", element_name(mesh.element)));
  const Index cells = mesh.cell_count();
  if (cells == 0) return;
  std::vector<Bounds> bounds(cells);
  Bounds all = cell_bounds(mesh, 0);
  for (Index e = 0; e < cells; ++e) {
    bounds[e] = cell_bounds(mesh, e);
    all.lo = all.lo.cwiseMin(bounds[e].lo);
    all.hi = all.hi.cwiseMax(bounds[e].hi);
  }
  // About one cell per bucket: n buckets along each axis in proportion to the extents.
  const int dim = mesh.dim;
  const Vec3 extent = (all.hi - all.lo).cwiseMax(1e-300);
  Real volume = 1;
  for (int k = 0; k < dim; ++k) volume *= extent[k];
  const Real side = std::pow(volume / static_cast<Real>(cells), 1.0 / dim);
  lo_ = all.lo;
  for (int k = 0; k < 3; ++k) {
    buckets_[k] = k < dim ? std::clamp(static_cast<int>(std::ceil(extent[k] / side)), 1, 4096) : 1;
    bucket_size_[k] = k < dim ? extent[k] / buckets_[k] : 1;
  }
  auto range = [&](const Bounds& b, int k) {
    if (k >= dim) return std::pair<int, int>{0, 0};
    const int i0 = std::clamp(static_cast<int>(std::floor((b.lo[k] - lo_[k]) / bucket_size_[k])), 0, buckets_[k] - 1);
    const int i1 = std::clamp(static_cast<int>(std::floor((b.hi[k] - lo_[k]) / bucket_size_[k])), 0, buckets_[k] - 1);
    return std::pair<int, int>{i0, i1};
  };
  // Two passes: count the cells per bucket, then fill them in cell order.
  const size_t bucket_count = static_cast<size_t>(buckets_[0]) * buckets_[1] * buckets_[2];
  bucket_start_.assign(bucket_count + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Index> next;
    if (pass == 1) {
      for (size_t b = 0; b < bucket_count; ++b) bucket_start_[b + 1] += bucket_start_[b];
      bucket_cells_.resize(bucket_start_[bucket_count]);
      next.assign(bucket_start_.begin(), bucket_start_.end() - 1);
    }
    for (Index e = 0; e < cells; ++e) {
      const auto [x0, x1] = range(bounds[e], 0);
      const auto [y0, y1] = range(bounds[e], 1);
      const auto [z0, z1] = range(bounds[e], 2);
      for (int k = z0; k <= z1; ++k)
        for (int j = y0; j <= y1; ++j)
          for (int i = x0; i <= x1; ++i) {
            const size_t b = (static_cast<size_t>(k) * buckets_[1] + j) * buckets_[0] + i;
            if (pass == 0)
              ++bucket_start_[b + 1];
            else
              bucket_cells_[next[b]++] = e;
          }
    }
  }
}

bool MeshLocator::inside_cell(Index e, const Vec3& point, MeshPoint& found) const {
  const Index* c = mesh_.cell(e);
  const int nodes = mesh_.nodes_per_cell(), dim = mesh_.dim;
  Real N[kMaxElementNodes];
  Vec3 dN[kMaxElementNodes];
  // Newton on x(xi) = point from the cell's centre; the map is bilinear (trilinear), so a few
  // iterations reach round-off for any reasonably shaped cell.
  Vec3 xi = Vec3::Zero();
  for (int it = 0; it < 30; ++it) {
    shape_functions(mesh_.element, xi, N, dN);
    Vec3 x = Vec3::Zero();
    for (int a = 0; a < nodes; ++a) x += N[a] * mesh_.nodes[c[a]];
    Vec3 d = cell_jacobian(mesh_, e, dN).inverse() * (point - x);
    for (int k = dim; k < 3; ++k) d[k] = 0;
    xi += d;
    if (!xi.allFinite() || xi.cwiseAbs().maxCoeff() > 10) return false;
    if (d.norm() < 1e-14) break;
  }
  for (int k = 0; k < dim; ++k)
    if (std::abs(xi[k]) > 1 + 1e-9) return false;
  found.cell = e;
  found.xi = xi;
  shape_functions(mesh_.element, xi, found.shape, dN);
  const Mat3 inverse_transpose = cell_jacobian(mesh_, e, dN).inverse().transpose();
  for (int a = 0; a < nodes; ++a) found.gradient[a] = inverse_transpose * dN[a];
  return true;
}

std::optional<MeshPoint> MeshLocator::locate(const Vec3& point, Index hint) const {
  if (bucket_cells_.empty()) return std::nullopt;
  MeshPoint found;
  if (hint >= 0 && inside_cell(hint, point, found)) return found;
  int index[3] = {0, 0, 0};
  for (int k = 0; k < mesh_.dim; ++k) {
    const Real s = (point[k] - lo_[k]) / bucket_size_[k];
    // Points on the far side of the box belong to the last bucket; farther ones are outside
    // unless within the slack a cell's own test allows.
    if (!(s >= -1e-6 && s <= buckets_[k] + 1e-6)) return std::nullopt;
    index[k] = std::clamp(static_cast<int>(std::floor(s)), 0, buckets_[k] - 1);
  }
  const size_t b = (static_cast<size_t>(index[2]) * buckets_[1] + index[1]) * buckets_[0] + index[0];
  for (Index i = bucket_start_[b]; i < bucket_start_[b + 1]; ++i)
    if (inside_cell(bucket_cells_[i], point, found)) return found;
  return std::nullopt;
}

}  // namespace moreau
