#include "moreau/fem/flow/flow_source_assembly.hpp"

#include "moreau/fem/core/newton.hpp"

namespace moreau {

namespace {

// f_A = -R_src,A / V_A on the free velocity dofs, zero elsewhere.
VectorX source_force_density(const NavierStokesModel& m, const VectorX& source_R) {
  VectorX density = VectorX::Zero(m.dof_count());
  for (Index n = 0; n < m.mesh.node_count(); ++n)
    for (int i = 0; i < m.dim(); ++i) {
      const Index d = m.dof(n, i);
      if (m.free_index[d] >= 0) density[d] = -source_R[d] / m.node_volume[n];
    }
  return density;
}

}  // namespace

void flow_residual_with_source(const NavierStokesModel& m, const VectorX& x, const FlowTimeStep& step,
                               const VectorX& source_R, VectorX& R) {
  const VectorX density = source_force_density(m, source_R);
  assemble_flow(m, x, step, R, nullptr, {}, {&density, nullptr});
  R += source_R;
}

void assemble_flow_with_source(const NavierStokesModel& m, const VectorX& x, const FlowTimeStep& step,
                               const FlowSource& source, const FlowAssembly& how, VectorX& R, SparseMatrix* J,
                               FlowLowRank* low_rank, double& source_s) {
  VectorX source_R = VectorX::Zero(m.dof_count());
  std::vector<Eigen::Triplet<Real, int>> source_entries;
  timed(source_s, [&] {
    source.add(x, step, source_R, J ? &source_entries : nullptr, J ? low_rank : nullptr);
    return 0;
  });
  // Per free column, -1 / V_A: the diagonal of P's right factor (zero on pressure columns).
  const VectorX density = source_force_density(m, source_R);
  VectorX inverse_volume = VectorX::Zero(m.free_count);
  for (Index n = 0; n < m.mesh.node_count(); ++n)
    for (int i = 0; i < m.dim(); ++i)
      if (const Index free = m.free_index[m.dof(n, i)]; free >= 0) inverse_volume[free] = -1 / m.node_volume[n];
  SparseMatrix S;
  assemble_flow(m, x, step, R, J, how, {&density, J ? &S : nullptr});
  R += source_R;
  if (!J) return;
  timed(source_s, [&] {
    // The source's entries join the cells' pattern (their union: an immersed solid's nodes move
    // between fluid cells, so the pattern may change from one evaluation to the next).
    SparseMatrix source_J(J->rows(), J->cols());
    source_J.setFromTriplets(source_entries.begin(), source_entries.end());
    const SparseMatrix P = S * inverse_volume.asDiagonal();
    *J += source_J + P * source_J;
    J->makeCompressed();
    if (low_rank && low_rank->U.cols() > 0) low_rank->U += P * low_rank->U;
    return 0;
  });
}

}  // namespace moreau
