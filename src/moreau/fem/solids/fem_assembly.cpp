#include "moreau/fem/solids/fem_assembly.hpp"

#include <functional>

#include "moreau/fem/solids/solid_partition.hpp"

namespace moreau {

namespace {

// The cells of solid `index` that this process assembles, in colours: all of them, or in a
// distributed run those that complete its rows.
const std::vector<std::vector<Index>>& assembled_cells(const FemModel& model, size_t index) {
  return model.partition ? model.partition->colours[index] : model.solids[index].colours;
}

// For every cell of solid `index` this process assembles: gathers its nodal values of u (and of
// u_next, if given), lets `compute(e, local_u, local_u_next, out)` fill the element output and
// `visit(e, out)` scatter it, by colours (for_each_cell_by_colour: race-free and deterministic).
template <class Compute, class Visit>
void for_each_cell(const FemModel& model, size_t index, const VectorX& u, const VectorX* u_next, int threads,
                   Compute compute, Visit visit) {
  const FemSolid& s = model.solids[index];
  const int dim = model.dim, nodes = s.mesh.nodes_per_cell();
  for_each_cell_by_colour(assembled_cells(model, index), threads, [&](Index e) {
    ElementOutput out;
    Real local_u[kMaxElementDofs], local_next[kMaxElementDofs];
    const Index* c = s.mesh.cell(e);
    for (int a = 0; a < nodes; ++a)
      for (int k = 0; k < dim; ++k) {
        const Index d = model.dof(s.node_begin + c[a], k);
        local_u[a * dim + k] = u[d];
        if (u_next) local_next[a * dim + k] = (*u_next)[d];
      }
    compute(e, local_u, local_next, out);
    visit(e, out);
  });
}

// Scatters cell outputs into the global force, tangent values and per-cell energies.
InternalForceResult scatter_cells(const FemModel& model, const VectorX& u, const VectorX* u_next, bool with_tangent,
                                  VectorX& force, SparseMatrix* tangent, int threads,
                                  const std::function<void(const FemSolid&, Index, const Real*, const Real*, ElementOutput&)>& compute) {
  InternalForceResult result;
  force.setZero(model.dof_count());
  if (tangent) {
    *tangent = model.pattern;
    std::fill(tangent->valuePtr(), tangent->valuePtr() + tangent->nonZeros(), 0.0);
  }
  Real* values = with_tangent && tangent ? tangent->valuePtr() : nullptr;
  const int dim = model.dim;
  // Per cell of every solid, numbered solid after solid: its energy and whether it is valid (1/0).
  Index cell_count = 0;
  for (const FemSolid& s : model.solids) cell_count += s.mesh.cell_count();
  VectorX cell_energy = VectorX::Zero(cell_count), cell_valid = VectorX::Ones(cell_count);
  Index first_cell = 0;
  for (size_t index = 0; index < model.solids.size(); ++index) {
    const FemSolid& s = model.solids[index];
    const int nodes = s.mesh.nodes_per_cell(), n = nodes * dim;
    for_each_cell(
        model, index, u, u_next, threads,
        [&](Index e, const Real* a, const Real* b, ElementOutput& out) { compute(s, e, a, b, out); },
        [&](Index e, const ElementOutput& out) {
          cell_energy[first_cell + e] = out.energy;
          if (!out.valid) {
            cell_valid[first_cell + e] = 0;
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
    first_cell += s.mesh.cell_count();
  }
  if (const SolidPartition* part = model.partition.get()) {
    part->dofs.complete(force);
    part->cells.complete(cell_energy);
    part->cells.complete(cell_valid);
  }
  // The energy summed in cell order, on every rank the same bits as on one process.
  first_cell = 0;
  for (const FemSolid& s : model.solids) {
    for (Index e = 0; e < s.mesh.cell_count(); ++e) {
      result.energy += cell_energy[first_cell + e];
      if (cell_valid[first_cell + e] == 0 && result.valid) {
        result.valid = false;
        result.invalid_solid = s.name;
        result.invalid_cell = e;
      }
    }
    first_cell += s.mesh.cell_count();
  }
  return result;
}

}  // namespace

InternalForceResult assemble_internal_forces(const FemModel& model, const VectorX& u, VectorX& force,
                                             SparseMatrix* tangent, int threads) {
  const bool with_tangent = tangent != nullptr;
  return scatter_cells(model, u, nullptr, with_tangent, force, tangent, threads,
                       [&](const FemSolid& s, Index e, const Real* local_u, const Real*, ElementOutput& out) {
                         solid_element(s.material, s.volume, s.cell_quadrature(e), model.dim, local_u, with_tangent, out);
                       });
}

InternalForceResult assemble_step_forces(const FemModel& model, const VectorX& u_n, const VectorX& u_next,
                                         StepRule rule, VectorX& force, SparseMatrix* tangent, int threads) {
  const bool with_tangent = tangent != nullptr;
  return scatter_cells(model, u_n, &u_next, with_tangent, force, tangent, threads,
                       [&](const FemSolid& s, Index e, const Real* a, const Real* b, ElementOutput& out) {
                         solid_element_step(s.material, s.volume, s.cell_quadrature(e), model.dim, a, b, rule, with_tangent, out);
                       });
}

VectorX tangent_times(const FemModel& model, const VectorX& u, const VectorX& direction) {
  VectorX product = VectorX::Zero(model.dof_count());
  const int dim = model.dim;
  for (size_t index = 0; index < model.solids.size(); ++index) {
    const FemSolid& s = model.solids[index];
    const int nodes = s.mesh.nodes_per_cell();
    for_each_cell(
        model, index, u, nullptr, 0,
        [&](Index e, const Real* local_u, const Real*, ElementOutput& out) {
          solid_element(s.material, s.volume, s.cell_quadrature(e), dim, local_u, true, out);
        },
        [&](Index e, const ElementOutput& out) {
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
  if (model.partition) model.partition->dofs.complete(product);
  return product;
}

SparseMatrix assemble_mass_matrix(const FemModel& model) {
  SparseMatrix M = model.pattern;
  std::fill(M.valuePtr(), M.valuePtr() + M.nonZeros(), 0.0);
  const int dim = model.dim;
  for (const FemSolid& s : model.solids) {
    const int nodes = s.mesh.nodes_per_cell(), n = nodes * dim;
    for (Index e = 0; e < s.mesh.cell_count(); ++e) {
      const Real* Me = s.cell_mass.data() + static_cast<size_t>(e) * nodes * nodes;
      const Index* slots = s.slots.data() + static_cast<size_t>(e) * n * n;
      for (int a = 0; a < nodes; ++a)
        for (int b = 0; b < nodes; ++b)
          for (int k = 0; k < dim; ++k) {
            const Index slot = slots[(a * dim + k) * n + b * dim + k];
            if (slot >= 0) M.valuePtr()[slot] += Me[a * nodes + b];
          }
    }
  }
  return M;
}

VectorX mass_times(const FemModel& model, const VectorX& x) {
  VectorX y = VectorX::Zero(model.dof_count());
  const int dim = model.dim;
  for (const FemSolid& s : model.solids) {
    const int nodes = s.mesh.nodes_per_cell();
    for (Index e = 0; e < s.mesh.cell_count(); ++e) {
      const Real* Me = s.cell_mass.data() + static_cast<size_t>(e) * nodes * nodes;
      const Index* c = s.mesh.cell(e);
      for (int a = 0; a < nodes; ++a)
        for (int b = 0; b < nodes; ++b)
          for (int k = 0; k < dim; ++k)
            y[model.dof(s.node_begin + c[a], k)] += Me[a * nodes + b] * x[model.dof(s.node_begin + c[b], k)];
    }
  }
  return y;
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

void apply_prescribed_velocity(const FemModel& model, Real t, VectorX& v) {
  const Real dt = 1e-6;
  for (const PrescribedDof& p : model.prescribed) v[p.dof] = (p.value(t + dt) - p.value(t - dt)) / (2 * dt);
}

VectorX free_part(const FemModel& model, const VectorX& full) { return gather_free(model.free_index, model.free_count, full); }

void add_free_part(const FemModel& model, const VectorX& free, VectorX& full) { add_free(model.free_index, free, full); }

}  // namespace moreau
