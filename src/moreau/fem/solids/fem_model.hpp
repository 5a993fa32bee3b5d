#pragma once
// The FEM engine's model: solids (a mesh, a hyperelastic material and its precomputed
// reference-configuration quadrature), the global numbering of nodes and degrees of freedom,
// the prescribed (Dirichlet) degrees of freedom, the loads, and the sparsity pattern that every
// tangent is assembled into. Built once from a scene; never changed by a run.
//
// Degrees of freedom: `dim` per node, node-major over all solids (solid s owns nodes
// [node_begin, node_begin + mesh.node_count())). The free ones are numbered 0..free_count-1 in the
// same order; matrices (tangent, mass) live on the free ones only.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "moreau/fem/core/cell_sparsity.hpp"
#include "moreau/fem/core/fem_mesh.hpp"
#include "moreau/fem/solids/solid_element.hpp"
#include "moreau/materials/hyperelastic.hpp"

namespace moreau {

struct SolidPartition;  // solid_partition.hpp

struct FemSolid {
  std::string name;
  FemMesh mesh;
  HyperelasticMaterial material;
  VolumeTreatment volume = VolumeTreatment::pointwise;  // mean_dilatation: Neo-Hookean, quad4/hex8
  Index node_begin = 0;
  // Stiffness quadrature (degree 2: 2x2(x2) Gauss on quads and hexes, one point on simplices).
  int points_per_cell = 0;
  std::vector<Real> weight;    // [cell][point]  w_gauss det(dX/dxi)
  std::vector<Vec3> gradient;  // [cell][point][node]  dN/dX
  // Consistent mass per cell, M_ab = integral of rho N_a N_b (the same for every component).
  std::vector<Real> cell_mass;  // [cell][a * nodes + b]
  // Cells grouped so that no two cells of a group share a node (parallel scatter without races).
  std::vector<std::vector<Index>> colours;
  // Per cell, per local (row, column) dof pair, the position in the tangent's value array (-1 when
  // either dof is prescribed).
  std::vector<Index> slots;    // [cell][row * n + column], n = dim * nodes per cell

  CellQuadrature cell_quadrature(Index e) const {
    return {points_per_cell, mesh.nodes_per_cell(), weight.data() + static_cast<size_t>(e) * points_per_cell,
            gradient.data() + static_cast<size_t>(e) * points_per_cell * mesh.nodes_per_cell()};
  }
};

/// A prescribed displacement component: u[dof] = value(t).
struct PrescribedDof {
  Index dof = 0;
  std::function<Real(Real)> value;
};

/// A load that scales one vector function of time by a fixed weight per node:
///   f_node = weight_node * value(t)
/// nodal forces (weight 1, value in N), tractions on reference areas (weight = integral of N_a
/// over the loaded facets, value in Pa) and body forces (weight = integral of rho N_a, value an
/// acceleration such as gravity, m/s^2).
struct NodalLoad {
  std::string name;
  std::vector<Index> nodes;    // global
  std::vector<Real> weights;
  std::function<Vec3(Real)> value;
};

struct FemModel {
  int dim = 3;
  std::vector<FemSolid> solids;
  Index node_count = 0;
  std::vector<Real> node_mass;    // per node, kg (2D: kg/m): the integral of rho N_a (row sums of M)
  std::vector<PrescribedDof> prescribed;
  std::vector<NodalLoad> loads;
  std::vector<Index> free_index;  // per dof; -1 if prescribed
  Index free_count = 0;
  SparseMatrix pattern;           // free x free, values zero: the structure of every tangent
                                  // (distributed: this rank's rows only)
  std::shared_ptr<const SolidPartition> partition;  // null unless divided among MPI ranks

  Index dof_count() const { return node_count * dim; }
  Index dof(Index node, int component) const { return node * dim + component; }
  /// Reference position of a global node.
  Vec3 reference_position(Index node) const;
  /// The solid that owns a global node and its local index.
  std::pair<const FemSolid*, Index> owner(Index node) const;
};

/// Numbers the dofs not in `prescribed` 0, 1, ... in order (free_index[d] = -1 for prescribed
/// ones; a dof prescribed twice counts once) and returns how many are free.
Index number_free_dofs(Index dof_count, const std::vector<PrescribedDof>& prescribed, std::vector<Index>& free_index);

/// Adds a solid (its quadrature is computed here); call finalize_fem_model after the last.
void add_fem_solid(FemModel& model, FemSolid solid);

/// Numbers the free degrees of freedom (after `prescribed` is complete; a dof prescribed twice
/// keeps its last value), colours the cells and builds the tangent's sparsity pattern.
void finalize_fem_model(FemModel& model);

/// Integral of N_a over the facets of a named boundary, per node of the boundary (sorted): the
/// weights of a traction on it. Facets are line2 in 2D (length per unit thickness), tri3/quad4 in 3D.
void facet_node_integrals(const FemSolid& solid, const std::string& boundary, std::vector<Index>& nodes,
                          std::vector<Real>& weights);

}  // namespace moreau
