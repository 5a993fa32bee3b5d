#pragma once
// The mesh of the FEM engine: nodes, cells of one element type, and named boundaries (sets of
// facets) and regions (sets of cells) that scenes refer to by name. 2D meshes lie in the xy plane
// (z = 0) and carry two degrees of freedom per node.
#include <array>
#include <string>
#include <vector>

#include "moreau/fem/core/elements.hpp"

namespace moreau {

struct FemBoundary {
  std::string name;
  std::vector<Index> facets;  // facet_type(element) nodes per facet, outward oriented
};

struct FemMesh {
  int dim = 3;                          // 2 or 3
  ElementType element = ElementType::hex8;
  std::vector<Vec3> nodes;              // m (z = 0 in 2D)
  std::vector<Index> cells;             // element_node_count(element) per cell
  std::vector<FemBoundary> boundaries;

  Index node_count() const { return static_cast<Index>(nodes.size()); }
  int nodes_per_cell() const { return element_node_count(element); }
  Index cell_count() const { return static_cast<Index>(cells.size()) / nodes_per_cell(); }
  const Index* cell(Index e) const { return cells.data() + static_cast<size_t>(e) * nodes_per_cell(); }
  /// The boundary of that name, or nullptr.
  const FemBoundary* boundary(const std::string& name) const;
  /// The nodes of a boundary, sorted and unique.
  std::vector<Index> boundary_nodes(const std::string& name) const;
};

/// dX/dxi of cell e at the point where the reference derivatives dN were taken (rows and columns
/// past the mesh dimension are identity, so the determinant is the area or volume ratio).
Mat3 cell_jacobian(const FemMesh& mesh, Index e, const Vec3* dN);

/// Facets that belong to exactly one cell, oriented outward, in cell order.
std::vector<Index> exterior_facets(const FemMesh& mesh);

/// The rectangle [min, max] in cells[0] x cells[1] quad4 cells, or each cut into two tri3 along
/// alternating diagonals. Boundaries "left" (x = min), "right", "bottom" (y = min), "top".
/// Node (i, j) is i + (cells[0] + 1) j.
FemMesh make_rectangle_mesh(const Vec2& min, const Vec2& max, const std::array<int, 2>& cells, ElementType element);

/// The box [min, max] in cells[0] x cells[1] x cells[2] hex8 cells, or each cut into six tet4.
/// Boundaries "left"/"right" (x), "bottom"/"top" (y), "back"/"front" (z = min / max).
/// Node (i, j, k) is (i (cells[1] + 1) + j)(cells[2] + 1) + k.
FemMesh make_box_mesh(const Vec3& min, const Vec3& max, const std::array<int, 3>& cells, ElementType element);

/// Removes the cells whose centre lies inside any of `boxes` (min, max corners; in 2D z is
/// ignored) from a mesh generated on the rectangle or box [min, max]: an L, a frame, a plate with
/// a slot. Nodes no cell uses are dropped. Boundaries are rebuilt: the generator's sides keep
/// their names for the facets that remain on them, and the newly exposed facets form "cut".
void remove_cells(FemMesh& mesh, const std::vector<std::array<Vec3, 2>>& boxes, const Vec3& min, const Vec3& max);

/// A FEM mesh from a Gmsh MSH 4.1 file (fem/gmsh_mesh.cpp): the cells are the elements of the
/// highest dimension (tri3 or quad4: a 2D mesh in the xy plane; tet4 or hex8: 3D), one type per
/// file; the nodes they use are kept in file order. Each physical group one dimension lower
/// becomes a boundary named by its physical name (or "physical_<tag>"). Problems are InputErrors
/// naming the file.
FemMesh read_gmsh_fem_mesh(const std::string& path);

/// Checks that every cell has a positive Jacobian determinant at its centre (add_fem_solid then
/// checks every quadrature point); a mesh
/// whose cells are all inverted (a file convention) is reordered, a mix is an InputError naming
/// `source`.
void orient_and_validate_cells(FemMesh& mesh, const std::string& source);

}  // namespace moreau
