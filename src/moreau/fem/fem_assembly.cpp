#include "moreau/fem/fem_assembly.hpp"

#include <omp.h>

namespace moreau {

namespace {

// Calls visit(e, out, local_u) for every cell of solid s with its element output computed at u,
// colour by colour, cells of a colour in parallel (they share no node, so visit may scatter into
// the nodes' global entries without races, and each entry sums its cells in colour order).
template <class Visit>
void for_each_cell(const FemModel& model, const FemSolid& s, const VectorX& u, bool with_tangent, Visit visit) {
  const int dim = model.dim, nodes = s.mesh.nodes_per_cell();
  for (const std::vector<Index>& colour : s.colours) {
    const Index count = static_cast<Index>(colour.size());
#pragma omp parallel num_threads(model.threads > 0 ? model.threads : omp_get_max_threads())
    {
      ElementOutput out;
      Real local_u[kMaxElementDofs];
#pragma omp for schedule(static)
      for (Index i = 0; i < count; ++i) {
        const Index e = colour[i];
        const Index* c = s.mesh.cell(e);
        for (int a = 0; a < nodes; ++a)
          for (int k = 0; k < dim; ++k) local_u[a * dim + k] = u[model.dof(s.node_begin + c[a], k)];
        solid_element(s.material, s.cell_quadrature(e), dim, local_u, with_tangent, out);
        visit(e, out);
      }
    }
  }
}

}  // namespace

InternalForceResult assemble_internal_forces(const FemModel& model, const VectorX& u, VectorX& force,
                                             SparseMatrix* tangent) {
  InternalForceResult result;
  force.setZero(model.dof_count());
  if (tangent) {
    *tangent = model.pattern;
    std::fill(tangent->valuePtr(), tangent->valuePtr() + tangent->nonZeros(), 0.0);
  }
  Real* values = tangent ? tangent->valuePtr() : nullptr;
  const int dim = model.dim;
  for (const FemSolid& s : model.solids) {
    const int nodes = s.mesh.nodes_per_cell(), n = nodes * dim;
    std::vector<Real> cell_energy(s.mesh.cell_count(), 0.0);
    std::vector<char> cell_valid(s.mesh.cell_count(), 1);
    for_each_cell(model, s, u, tangent != nullptr, [&](Index e, const ElementOutput& out) {
      cell_energy[e] = out.energy;
      if (!out.valid) {
        cell_valid[e] = 0;
        return;
      }
      const Index* c = s.mesh.cell(e);
      for (int a = 0; a < nodes; ++a)
        for (int k = 0; k < dim; ++k) force[model.dof(s.node_begin + c[a], k)] += out.force[a * dim + k];
      if (!values) return;
      const Index* slots = s.slots.data() + static_cast<size_t>(e) * n * n;
      for (int r = 0; r < n; ++r)
        for (int q = 0; q < n; ++q)
          if (slots[r * n + q] >= 0) values[slots[r * n + q]] += out.tangent(r, q);
    });
    for (Index e = 0; e < s.mesh.cell_count(); ++e) {
      result.energy += cell_energy[e];
      if (!cell_valid[e] && result.valid) {
        result.valid = false;
        result.invalid_solid = s.name;
        result.invalid_cell = e;
      }
    }
  }
  return result;
}

VectorX tangent_times(const FemModel& model, const VectorX& u, const VectorX& direction) {
  VectorX product = VectorX::Zero(model.dof_count());
  const int dim = model.dim;
  for (const FemSolid& s : model.solids) {
    const int nodes = s.mesh.nodes_per_cell();
    for_each_cell(model, s, u, true, [&](Index e, const ElementOutput& out) {
      if (!out.valid) return;
      const Index* c = s.mesh.cell(e);
      ElementVector d(nodes * dim);
      for (int a = 0; a < nodes; ++a)
        for (int k = 0; k < dim; ++k) d[a * dim + k] = direction[model.dof(s.node_begin + c[a], k)];
      const ElementVector Kd = out.tangent * d;
      for (int a = 0; a < nodes; ++a)
        for (int k = 0; k < dim; ++k) product[model.dof(s.node_begin + c[a], k)] += Kd[a * dim + k];
    });
  }
  return product;
}

VectorX external_forces(const FemModel& model, Real t) {
  VectorX f = VectorX::Zero(model.dof_count());
  for (const NodalLoad& load : model.loads) {
    const Vec3 value = load.value(t);
    for (size_t i = 0; i < load.nodes.size(); ++i)
      for (int k = 0; k < model.dim; ++k) f[model.dof(load.nodes[i], k)] += load.weights[i] * value[k];
  }
  return f;
}

void apply_prescribed(const FemModel& model, Real t, VectorX& u) {
  for (const PrescribedDof& p : model.prescribed) u[p.dof] = p.value(t);
}

VectorX free_part(const FemModel& model, const VectorX& full) {
  VectorX free(model.free_count);
  for (Index d = 0; d < model.dof_count(); ++d)
    if (model.free_index[d] >= 0) free[model.free_index[d]] = full[d];
  return free;
}

void add_free_part(const FemModel& model, const VectorX& free, VectorX& full) {
  for (Index d = 0; d < model.dof_count(); ++d)
    if (model.free_index[d] >= 0) full[d] += free[model.free_index[d]];
}

}  // namespace moreau
