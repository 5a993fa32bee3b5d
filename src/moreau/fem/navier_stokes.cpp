#include "moreau/fem/navier_stokes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "moreau/errors.hpp"

namespace moreau {

namespace {

constexpr int kMaxFields = 4;
constexpr int kMaxCellDofs = kMaxFields * kMaxElementNodes;
using CellVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxCellDofs, 1>;
using CellMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCellDofs, kMaxCellDofs>;

// The residual and the Jacobian (tau frozen) of one cell; local dofs node-major, fields
// (velocity components, pressure).
void flow_cell(const NavierStokesModel& m, Index e, const Real* x, const Real* x_old, Real dt, bool with_jacobian,
               CellVector& R, CellMatrix& J) {
  const int dim = m.dim, F = m.fields(), nodes = m.mesh.nodes_per_cell(), n = F * nodes;
  const Real rho = m.density, mu = m.viscosity, nu = mu / rho;
  const Real ct = dt > 0 ? 1 / dt : 0;
  R.setZero(n);
  if (with_jacobian) J.setZero(n, n);
  const Real h = m.cell_size[e];
  Real adv[kMaxElementNodes];
  for (int q = 0; q < m.points; ++q) {
    const size_t qp = static_cast<size_t>(e) * m.points + q;
    const Real w = m.weight[qp];
    const Real* N = m.shape.data() + qp * nodes;
    const Vec3* dN = m.gradient.data() + qp * nodes;
    Vec3 u = Vec3::Zero(), u_old = Vec3::Zero(), gp = Vec3::Zero();
    Mat3 G = Mat3::Zero();  // G_ij = du_i / dx_j
    Real p = 0;
    for (int a = 0; a < nodes; ++a) {
      for (int i = 0; i < dim; ++i) {
        u[i] += N[a] * x[a * F + i];
        if (x_old) u_old[i] += N[a] * x_old[a * F + i];
        G.row(i) += x[a * F + i] * dN[a].transpose();
      }
      p += N[a] * x[a * F + dim];
      gp += x[a * F + dim] * dN[a];
    }
    const Vec3 ut = ct * (u - u_old);
    // Strong momentum residual (gradients have zero components past dim, so 3-vector dot
    // products below are the dim-dimensional ones).
    const Vec3 r = rho * (ut + G * u - m.body_force) + gp;
    Real s1 = 0;
    for (int a = 0; a < nodes; ++a) {
      adv[a] = u.dot(dN[a]);
      s1 += std::abs(adv[a]);
    }
    // tau = (tau1^-2 + tau2^-2 + tau3^-2)^-1/2 with tau1^-1 = sum_a |u . grad N_a|, tau2 = dt/2,
    // tau3 = h^2 / (4 nu).
    const Real inv = s1 * s1 + (dt > 0 ? 4 * ct * ct : 0) + std::pow(4 * nu / (h * h), 2);
    const Real tau = m.fixed_tau > 0 ? m.fixed_tau : 1 / std::sqrt(inv);
    const Real nu_lsic = m.fixed_tau > 0 ? m.fixed_lsic : tau * u.squaredNorm();
    const Real div = G.trace();
    for (int a = 0; a < nodes; ++a) {
      for (int i = 0; i < dim; ++i) {
        Real viscous = 0;
        for (int k = 0; k < dim; ++k) viscous += (G(i, k) + G(k, i)) * dN[a][k];
        R[a * F + i] += w * (N[a] * rho * (ut[i] + (G * u)[i] - m.body_force[i]) + mu * viscous - p * dN[a][i] +
                             tau * adv[a] * r[i] + nu_lsic * rho * dN[a][i] * div);
      }
      R[a * F + dim] += w * (N[a] * div + tau / rho * dN[a].dot(r));
    }
    if (!with_jacobian) continue;
    for (int a = 0; a < nodes; ++a)
      for (int b = 0; b < nodes; ++b) {
        const Real mass_adv = N[b] * ct + adv[b];
        const Real grad_dot = dN[a].dot(dN[b]);
        for (int j = 0; j < dim; ++j) {
          // d r_i / d u_bj = rho ((N_b / dt + u . grad N_b) delta_ij + G_ij N_b)
          Vec3 dr = rho * G.col(j) * N[b];
          dr[j] += rho * mass_adv;
          for (int i = 0; i < dim; ++i) {
            Real v = N[a] * dr[i] + mu * ((i == j ? grad_dot : 0) + dN[a][j] * dN[b][i]) + tau * adv[a] * dr[i] +
                     tau * N[b] * dN[a][j] * r[i] + nu_lsic * rho * dN[a][i] * dN[b][j];
            J(a * F + i, b * F + j) += w * v;
          }
          J(a * F + dim, b * F + j) += w * (N[a] * dN[b][j] + tau / rho * dN[a].dot(dr));
        }
        for (int i = 0; i < dim; ++i) J(a * F + i, b * F + dim) += w * (-dN[a][i] * N[b] + tau * adv[a] * dN[b][i]);
        J(a * F + dim, b * F + dim) += w * tau / rho * grad_dot;
      }
  }
}

}  // namespace

void assemble_flow(const NavierStokesModel& m, const VectorX& x, const VectorX* x_old, Real dt, VectorX& R,
                   SparseMatrix* J) {
  const int F = m.fields(), nodes = m.mesh.nodes_per_cell(), n = F * nodes;
  R.setZero(m.dof_count());
  if (J) {
    *J = m.pattern;
    std::fill(J->valuePtr(), J->valuePtr() + J->nonZeros(), 0.0);
  }
  for_each_cell_by_colour(m.colours, m.threads, [&](Index e) {
    CellVector Re;
    CellMatrix Je;
    Real local[kMaxCellDofs], local_old[kMaxCellDofs];
    const Index* c = m.mesh.cell(e);
    for (int a = 0; a < nodes; ++a)
      for (int f = 0; f < F; ++f) {
        local[a * F + f] = x[m.dof(c[a], f)];
        if (x_old) local_old[a * F + f] = (*x_old)[m.dof(c[a], f)];
      }
    flow_cell(m, e, local, x_old ? local_old : nullptr, dt, J != nullptr, Re, Je);
    for (int a = 0; a < nodes; ++a)
      for (int f = 0; f < F; ++f) R[m.dof(c[a], f)] += Re[a * F + f];
    if (!J) return;
    const Index* slots = m.slots.data() + static_cast<size_t>(e) * n * n;
    for (int r = 0; r < n; ++r)
      for (int q = 0; q < n; ++q)
        if (slots[r * n + q] >= 0) J->valuePtr()[slots[r * n + q]] += Je(r, q);
  });
}


void setup_navier_stokes(NavierStokesModel& m) {
  FemMesh& mesh = m.mesh;
  if (mesh.element != ElementType::quad4 && mesh.element != ElementType::hex8)
    throw InputError(fmt::format("the flow solver uses quad4 (2D) or hex8 (3D) cells, not {}", element_name(mesh.element)));
  m.dim = mesh.dim;
  const int nodes = mesh.nodes_per_cell(), F = m.fields();
  const auto rule = gauss_rule(mesh.element, 2);
  m.points = static_cast<int>(rule.size());
  const size_t qps = static_cast<size_t>(mesh.cell_count()) * rule.size();
  m.weight.assign(qps, 0);
  m.shape.assign(qps * nodes, 0);
  m.gradient.assign(qps * nodes, Vec3::Zero());
  m.cell_size.assign(mesh.cell_count(), 0);
  Real N[kMaxElementNodes];
  Vec3 dN[kMaxElementNodes];
  for (Index e = 0; e < mesh.cell_count(); ++e) {
    Real measure = 0;
    for (size_t q = 0; q < rule.size(); ++q) {
      shape_functions(mesh.element, rule[q].xi, N, dN);
      const Mat3 Jac = cell_jacobian(mesh, e, dN);
      const Real det = Jac.determinant();
      if (!(det > 0)) throw InputError(fmt::format("flow mesh: cell {} is inverted or degenerate", e));
      const Mat3 inv_t = Jac.inverse().transpose();
      const size_t qp = static_cast<size_t>(e) * rule.size() + q;
      m.weight[qp] = rule[q].weight * det;
      measure += m.weight[qp];
      for (int a = 0; a < nodes; ++a) {
        m.shape[qp * nodes + a] = N[a];
        Vec3 g = inv_t * dN[a];
        for (int k = m.dim; k < 3; ++k) g[k] = 0;
        m.gradient[qp * nodes + a] = g;
      }
    }
    m.cell_size[e] = std::pow(measure, 1.0 / m.dim);
  }
  m.colours = colour_cells(mesh);
  m.free_count = number_free_dofs(m.dof_count(), m.prescribed, m.free_index);
  std::vector<Eigen::Triplet<Real, int>> entries;
  add_cell_couplings(mesh, 0, F, m.free_index, entries);
  m.pattern.resize(m.free_count, m.free_count);
  m.pattern.setFromTriplets(entries.begin(), entries.end());
  m.pattern.makeCompressed();
  m.slots = cell_slots(mesh, 0, F, m.free_index, m.pattern);
}

NewtonResult solve_navier_stokes(const NavierStokesModel& m, Real t, Real dt, const VectorX& x_old, VectorX& x,
                                 SparseLuSolver& solver, const NewtonSettings& settings) {
  NewtonResult result;
  for (const PrescribedDof& p : m.prescribed) x[p.dof] = p.value(t);
  VectorX R;
  SparseMatrix J;
  const VectorX* old = dt > 0 ? &x_old : nullptr;
  Real first = 0;
  for (;;) {
    timed(result.assembly_s, [&] { assemble_flow(m, x, old, dt, R, &J); return 0; });
    const VectorX r = gather_free(m.free_index, m.free_count, R);
    const Real norm = r.norm();
    result.residual_norms.push_back(norm);
    if (result.iterations == 0) first = std::max(norm, Real(1e-300));
    if (norm <= settings.tolerance * first || norm == 0) break;
    if (result.iterations == settings.max_iterations) {
      result.failure = fmt::format("the flow solve did not converge in {} Newton iterations (|R| = {:.3e}, first {:.3e})",
                                   settings.max_iterations, norm, first);
      return result;
    }
    const bool ok = timed(result.solve_s, [&] { return solver.factorize(J); });
    if (!ok) {
      result.failure = "the flow Jacobian is singular (is the pressure fixed somewhere, or an outflow given?)";
      return result;
    }
    const VectorX rhs = -r;
    const VectorX dx = timed(result.solve_s, [&] { return solver.solve(rhs); });
    ++result.iterations;
    add_free(m.free_index, dx, x);
    if (dx.norm() <= settings.tolerance * gather_free(m.free_index, m.free_count, x).norm()) {
      assemble_flow(m, x, old, dt, R, nullptr);
      result.residual_norms.push_back(gather_free(m.free_index, m.free_count, R).norm());
      break;
    }
  }
  result.converged = true;
  return result;
}

bool sample_flow(const NavierStokesModel& m, const VectorX& x, const Vec3& point, Vec3& velocity, Real& pressure) {
  const FemMesh& mesh = m.mesh;
  const int nodes = mesh.nodes_per_cell();
  Real N[kMaxElementNodes];
  Vec3 dN[kMaxElementNodes];
  for (Index e = 0; e < mesh.cell_count(); ++e) {
    const Index* c = mesh.cell(e);
    Vec3 lo = mesh.nodes[c[0]], hi = lo;
    for (int a = 1; a < nodes; ++a) {
      lo = lo.cwiseMin(mesh.nodes[c[a]]);
      hi = hi.cwiseMax(mesh.nodes[c[a]]);
    }
    const Real slack = 1e-9 * (hi - lo).norm();
    bool outside = false;
    for (int k = 0; k < m.dim; ++k) outside = outside || point[k] < lo[k] - slack || point[k] > hi[k] + slack;
    if (outside) continue;
    // Invert x(xi) = sum_a N_a(xi) X_a by Newton from the centre.
    Vec3 xi = Vec3::Zero();
    for (int it = 0; it < 30; ++it) {
      shape_functions(mesh.element, xi, N, dN);
      Vec3 xr = Vec3::Zero();
      for (int a = 0; a < nodes; ++a) xr += N[a] * mesh.nodes[c[a]];
      const Mat3 Jac = cell_jacobian(mesh, e, dN);
      Vec3 d = Jac.inverse() * (point - xr);
      for (int k = m.dim; k < 3; ++k) d[k] = 0;
      xi += d;
      if (d.norm() < 1e-14) break;
    }
    bool inside = true;
    for (int k = 0; k < m.dim; ++k) inside = inside && std::abs(xi[k]) <= 1 + 1e-9;
    if (!inside) continue;
    shape_functions(mesh.element, xi, N, dN);
    velocity.setZero();
    pressure = 0;
    for (int a = 0; a < nodes; ++a) {
      for (int k = 0; k < m.dim; ++k) velocity[k] += N[a] * x[m.dof(c[a], k)];
      pressure += N[a] * x[m.dof(c[a], m.dim)];
    }
    return true;
  }
  return false;
}

}  // namespace moreau
