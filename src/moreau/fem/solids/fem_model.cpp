#include "moreau/fem/solids/fem_model.hpp"

#include "moreau/fem/core/cell_sparsity.hpp"

#include <fmt/format.h>

#include "moreau/errors.hpp"

#include <algorithm>
#include <stdexcept>

namespace moreau {

namespace {

int stiffness_degree(ElementType type) { return type == ElementType::tri3 || type == ElementType::tet4 ? 1 : 2; }

}  // namespace

Vec3 FemModel::reference_position(Index node) const {
  const auto [solid, local] = owner(node);
  return solid->mesh.nodes[local];
}

std::pair<const FemSolid*, Index> FemModel::owner(Index node) const {
  for (const FemSolid& s : solids)
    if (node >= s.node_begin && node < s.node_begin + s.mesh.node_count()) return {&s, node - s.node_begin};
  throw std::out_of_range("node outside every solid");
}

void add_fem_solid(FemModel& model, FemSolid solid) {
  if (solid.mesh.dim != model.dim) throw std::logic_error("a solid's mesh dimension differs from the model's");
  if (solid.volume == VolumeTreatment::mean_dilatation &&
      (solid.material.model != HyperelasticModel::neo_hookean ||
       (solid.mesh.element != ElementType::quad4 && solid.mesh.element != ElementType::hex8)))
    throw std::logic_error("mean dilatation needs a Neo-Hookean material on quad4 or hex8 cells");
  const FemMesh& mesh = solid.mesh;
  const auto rule = gauss_rule(mesh.element, stiffness_degree(mesh.element));
  const int nodes = mesh.nodes_per_cell();
  solid.points_per_cell = static_cast<int>(rule.size());
  solid.weight.resize(static_cast<size_t>(mesh.cell_count()) * rule.size());
  solid.gradient.resize(solid.weight.size() * nodes);
  Real N[kMaxElementNodes];
  Vec3 dN[kMaxElementNodes];
  for (Index e = 0; e < mesh.cell_count(); ++e)
    for (size_t p = 0; p < rule.size(); ++p) {
      shape_functions(mesh.element, rule[p].xi, N, dN);
      const Mat3 J = cell_jacobian(mesh, e, dN);
      if (!(J.determinant() > 0))
        throw InputError(fmt::format("solid '{}': cell {} ({}) is inverted or degenerate at a quadrature point (det dX/dxi = {:.3g})",
                                     solid.name, e, element_name(mesh.element), J.determinant()));
      const Mat3 Jinv_t = J.inverse().transpose();
      const size_t qp = static_cast<size_t>(e) * rule.size() + p;
      solid.weight[qp] = rule[p].weight * J.determinant();
      for (int a = 0; a < nodes; ++a) {
        Vec3 g = Jinv_t * dN[a];
        for (int k = mesh.dim; k < 3; ++k) g[k] = 0;
        solid.gradient[qp * nodes + a] = g;
      }
    }
  // Consistent mass with a degree-2 rule (exact for affine cells; quads and hexes use 2 points per
  // direction either way).
  const auto mass_rule = gauss_rule(mesh.element, 2);
  solid.cell_mass.assign(static_cast<size_t>(mesh.cell_count()) * nodes * nodes, 0.0);
  for (Index e = 0; e < mesh.cell_count(); ++e)
    for (const QuadraturePoint& q : mass_rule) {
      shape_functions(mesh.element, q.xi, N, dN);
      const Real w = solid.material.density * q.weight * cell_jacobian(mesh, e, dN).determinant();
      Real* Me = solid.cell_mass.data() + static_cast<size_t>(e) * nodes * nodes;
      for (int a = 0; a < nodes; ++a)
        for (int b = 0; b < nodes; ++b) Me[a * nodes + b] += w * N[a] * N[b];
    }
  solid.node_begin = model.node_count;
  model.node_count += mesh.node_count();
  // Node masses: the row sums of the consistent mass, i.e. the integrals of rho N_a.
  model.node_mass.resize(model.node_count, 0.0);
  for (Index e = 0; e < mesh.cell_count(); ++e)
    for (int a = 0; a < nodes; ++a)
      for (int b = 0; b < nodes; ++b)
        model.node_mass[solid.node_begin + mesh.cell(e)[a]] += solid.cell_mass[static_cast<size_t>(e) * nodes * nodes + a * nodes + b];
  model.solids.push_back(std::move(solid));
}

Index number_free_dofs(Index dof_count, const std::vector<PrescribedDof>& prescribed, std::vector<Index>& free_index) {
  free_index.assign(dof_count, 0);
  for (const PrescribedDof& p : prescribed) free_index[p.dof] = -1;
  Index count = 0;
  for (Index d = 0; d < dof_count; ++d)
    if (free_index[d] >= 0) free_index[d] = count++;
  return count;
}

void finalize_fem_model(FemModel& model) {
  model.free_count = number_free_dofs(model.dof_count(), model.prescribed, model.free_index);
  std::vector<MeshNodes> meshes;
  for (const FemSolid& s : model.solids) meshes.push_back({&s.mesh, s.node_begin});
  model.pattern = cell_coupling_pattern(meshes, model.node_count, model.dim, model.free_index, model.free_count);
  for (FemSolid& s : model.solids) {
    s.colours = colour_cells(s.mesh);
    s.slots = cell_slots(s.mesh, s.node_begin, model.dim, model.free_index, model.pattern);
  }
}

void facet_node_integrals(const FemSolid& solid, const std::string& name, std::vector<Index>& nodes,
                          std::vector<Real>& weights) {
  const FemMesh& mesh = solid.mesh;
  const FemBoundary* boundary = mesh.boundary(name);
  nodes = mesh.boundary_nodes(name);
  weights.assign(nodes.size(), 0.0);
  if (!boundary) return;
  const ElementType type = facet_type(mesh.element);
  const int per = element_node_count(type);
  const auto rule = gauss_rule(type, 2);
  Real N[kMaxElementNodes];
  Vec3 dN[kMaxElementNodes];
  for (size_t f = 0; f < boundary->facets.size(); f += per)
    for (const QuadraturePoint& q : rule) {
      shape_functions(type, q.xi, N, dN);
      Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();
      for (int a = 0; a < per; ++a) {
        t1 += mesh.nodes[boundary->facets[f + a]] * dN[a].x();
        t2 += mesh.nodes[boundary->facets[f + a]] * dN[a].y();
      }
      const Real measure = type == ElementType::line2 ? t1.norm() : t1.cross(t2).norm();
      for (int a = 0; a < per; ++a) {
        const size_t i = std::lower_bound(nodes.begin(), nodes.end(), boundary->facets[f + a]) - nodes.begin();
        weights[i] += N[a] * q.weight * measure;
      }
    }
}

}  // namespace moreau
