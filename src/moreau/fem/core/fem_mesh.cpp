#include "moreau/fem/core/fem_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "moreau/errors.hpp"
#include "moreau/geometry/mesh_generators.hpp"

namespace moreau {

const FemBoundary* FemMesh::boundary(const std::string& name) const {
  for (const FemBoundary& b : boundaries)
    if (b.name == name) return &b;
  return nullptr;
}

std::vector<Index> FemMesh::boundary_nodes(const std::string& name) const {
  const FemBoundary* b = boundary(name);
  if (!b) return {};
  std::vector<Index> nodes = b->facets;
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

Mat3 cell_jacobian(const FemMesh& mesh, Index e, const Vec3* dN) {
  Mat3 J = Mat3::Zero();
  const Index* c = mesh.cell(e);
  for (int a = 0; a < mesh.nodes_per_cell(); ++a) J += mesh.nodes[c[a]] * dN[a].transpose();
  for (int k = mesh.dim; k < 3; ++k) J(k, k) = 1;
  return J;
}

std::vector<Index> exterior_facets(const FemMesh& mesh) {
  const auto& local = element_facets(mesh.element);
  // Key: the facet's sorted nodes; value: how often it was seen and its first oriented copy.
  std::map<std::vector<Index>, std::pair<int, std::vector<Index>>> seen;
  std::vector<std::vector<Index>> order;
  for (Index e = 0; e < mesh.cell_count(); ++e) {
    const Index* c = mesh.cell(e);
    for (const auto& f : local) {
      std::vector<Index> facet;
      for (int a : f) facet.push_back(c[a]);
      std::vector<Index> key = facet;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = seen.try_emplace(key, 0, facet);
      if (inserted) order.push_back(key);
      ++it->second.first;
    }
  }
  std::vector<Index> facets;
  for (const auto& key : order) {
    const auto& [count, facet] = seen.at(key);
    if (count == 1) facets.insert(facets.end(), facet.begin(), facet.end());
  }
  return facets;
}

namespace {

// Sorts the exterior facets into the named sides of an axis-aligned box: a facet whose nodes all
// lie on a side's plane belongs to it.
void add_box_sides(FemMesh& mesh, const Vec3& min, const Vec3& max) {
  const std::vector<Index> facets = exterior_facets(mesh);
  const int per = element_node_count(facet_type(mesh.element));
  static const char* names[3][2] = {{"left", "right"}, {"bottom", "top"}, {"back", "front"}};
  const Real tolerance = 1e-9 * (max - min).norm();
  for (int axis = 0; axis < mesh.dim; ++axis)
    for (int side = 0; side < 2; ++side) {
      FemBoundary b{names[axis][side], {}};
      const Real plane = side == 0 ? min[axis] : max[axis];
      for (size_t f = 0; f < facets.size(); f += per) {
        bool on = true;
        for (int a = 0; a < per; ++a) on = on && std::abs(mesh.nodes[facets[f + a]][axis] - plane) <= tolerance;
        if (on) b.facets.insert(b.facets.end(), facets.begin() + f, facets.begin() + f + per);
      }
      mesh.boundaries.push_back(std::move(b));
    }
}

// det dX/dxi at the cell's centre (its sign is the cell's orientation).
Real centre_jacobian(const FemMesh& mesh, Index e) {
  Real N[kMaxElementNodes];
  Vec3 dN[kMaxElementNodes];
  const Vec3 centre = mesh.element == ElementType::tri3   ? Vec3(1.0 / 3, 1.0 / 3, 0)
                      : mesh.element == ElementType::tet4 ? Vec3::Constant(0.25)
                                                          : Vec3::Zero();
  shape_functions(mesh.element, centre, N, dN);
  return cell_jacobian(mesh, e, dN).determinant();
}

// Reverses a cell's orientation by a reflection of its local numbering.
void reverse_cell(ElementType type, Index* c) {
  switch (type) {
    case ElementType::line2: std::swap(c[0], c[1]); break;
    case ElementType::tri3: std::swap(c[1], c[2]); break;
    case ElementType::quad4: std::swap(c[1], c[3]); break;
    case ElementType::tet4: std::swap(c[2], c[3]); break;
    case ElementType::hex8:
      std::swap(c[1], c[3]);
      std::swap(c[5], c[7]);
      break;
  }
}

}  // namespace

FemMesh make_rectangle_mesh(const Vec2& min, const Vec2& max, const std::array<int, 2>& cells, ElementType element) {
  FemMesh mesh;
  mesh.dim = 2;
  mesh.element = element;
  const int nx = cells[0], ny = cells[1];
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      mesh.nodes.emplace_back(min.x() + (max.x() - min.x()) * i / nx, min.y() + (max.y() - min.y()) * j / ny, 0.0);
  auto id = [nx](int i, int j) { return static_cast<Index>(i + (nx + 1) * j); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (element == ElementType::quad4) {
        mesh.cells.insert(mesh.cells.end(), {a, b, c, d});
      } else if ((i + j) % 2 == 0) {
        mesh.cells.insert(mesh.cells.end(), {a, b, c, a, c, d});
      } else {
        mesh.cells.insert(mesh.cells.end(), {a, b, d, b, c, d});
      }
    }
  add_box_sides(mesh, Vec3(min.x(), min.y(), 0), Vec3(max.x(), max.y(), 0));
  return mesh;
}

FemMesh make_box_mesh(const Vec3& min, const Vec3& max, const std::array<int, 3>& cells, ElementType element) {
  FemMesh mesh;
  mesh.dim = 3;
  mesh.element = element;
  if (element == ElementType::tet4) {
    const TetMesh tets = make_box_tets(min, max, cells, CellSplit::six);
    mesh.nodes = tets.vertices;
    for (const auto& t : tets.tets) mesh.cells.insert(mesh.cells.end(), t.begin(), t.end());
  } else {
    const int ny = cells[1] + 1, nz = cells[2] + 1;
    const Vec3 step = (max - min).cwiseQuotient(Vec3(cells[0], cells[1], cells[2]));
    for (int i = 0; i <= cells[0]; ++i)
      for (int j = 0; j < ny; ++j)
        for (int k = 0; k < nz; ++k) mesh.nodes.push_back(min + Vec3(i * step.x(), j * step.y(), k * step.z()));
    auto id = [ny, nz](int i, int j, int k) { return static_cast<Index>((i * ny + j) * nz + k); };
    for (int i = 0; i < cells[0]; ++i)
      for (int j = 0; j < cells[1]; ++j)
        for (int k = 0; k < cells[2]; ++k)
          mesh.cells.insert(mesh.cells.end(), {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                                               id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                                               id(i, j + 1, k + 1)});
  }
  add_box_sides(mesh, min, max);
  return mesh;
}

void remove_cells(FemMesh& mesh, const std::vector<std::array<Vec3, 2>>& boxes, const Vec3& min, const Vec3& max) {
  const int per = mesh.nodes_per_cell();
  std::vector<Index> kept_cells;
  std::vector<Index> renumber(mesh.node_count(), -1);
  std::vector<Vec3> nodes;
  for (Index e = 0; e < mesh.cell_count(); ++e) {
    Vec3 centre = Vec3::Zero();
    for (int a = 0; a < per; ++a) centre += mesh.nodes[mesh.cell(e)[a]] / per;
    bool inside_any = false;
    for (const auto& box : boxes) {
      bool inside = true;
      for (int k = 0; k < mesh.dim; ++k) inside = inside && centre[k] > box[0][k] && centre[k] < box[1][k];
      inside_any = inside_any || inside;
    }
    if (inside_any) continue;
    for (int a = 0; a < per; ++a) {
      Index& n = renumber[mesh.cell(e)[a]];
      if (n < 0) {
        n = static_cast<Index>(nodes.size());
        nodes.push_back(mesh.nodes[mesh.cell(e)[a]]);
      }
      kept_cells.push_back(n);
    }
  }
  mesh.nodes = std::move(nodes);
  mesh.cells = std::move(kept_cells);
  mesh.boundaries.clear();
  add_box_sides(mesh, min, max);
  // The facets on no side of the original domain were opened by the removal.
  std::vector<std::vector<Index>> named;
  const int facet = element_node_count(facet_type(mesh.element));
  for (const FemBoundary& b : mesh.boundaries)
    for (size_t f = 0; f < b.facets.size(); f += facet) {
      std::vector<Index> key(b.facets.begin() + f, b.facets.begin() + f + facet);
      std::sort(key.begin(), key.end());
      named.push_back(key);
    }
  std::sort(named.begin(), named.end());
  FemBoundary cut{"cut", {}};
  const std::vector<Index> exterior = exterior_facets(mesh);
  for (size_t f = 0; f < exterior.size(); f += facet) {
    std::vector<Index> key(exterior.begin() + f, exterior.begin() + f + facet);
    std::sort(key.begin(), key.end());
    if (!std::binary_search(named.begin(), named.end(), key))
      cut.facets.insert(cut.facets.end(), exterior.begin() + f, exterior.begin() + f + facet);
  }
  mesh.boundaries.push_back(std::move(cut));
}

void orient_and_validate_cells(FemMesh& mesh, const std::string& source) {
  Index negative = 0, degenerate = 0;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& x : mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  Real size = 0;
  for (int k = 0; k < mesh.dim && !mesh.nodes.empty(); ++k) size = std::max(size, hi[k] - lo[k]);
  const Real tiny = 1e-12 * std::pow(std::max(size, Real(1e-300)), mesh.dim);
  for (Index e = 0; e < mesh.cell_count(); ++e) {
    const Real det = centre_jacobian(mesh, e);
    negative += det < 0;
    degenerate += std::abs(det) <= tiny;
  }
  if (degenerate > 0)
    throw InputError(fmt::format("{}: {} of {} {} cells are degenerate (zero volume)", source, degenerate,
                                 mesh.cell_count(), element_name(mesh.element)));
  if (negative == 0) return;
  if (negative != mesh.cell_count())
    throw InputError(fmt::format("{}: {} of {} {} cells are inverted (negative Jacobian) while the others are not",
                                 source, negative, mesh.cell_count(), element_name(mesh.element)));
  for (Index e = 0; e < mesh.cell_count(); ++e)
    reverse_cell(mesh.element, mesh.cells.data() + static_cast<size_t>(e) * mesh.nodes_per_cell());
  for (FemBoundary& b : mesh.boundaries) {
    const int per = element_node_count(facet_type(mesh.element));
    for (size_t f = 0; f < b.facets.size(); f += per) std::reverse(b.facets.begin() + f, b.facets.begin() + f + per);
  }
}

}  // namespace moreau
