#include "moreau/fem/flow/navier_stokes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "moreau/errors.hpp"
#include "moreau/fem/core/newton.hpp"
#include "moreau/fem/distributed/mesh_partition.hpp"
#include "moreau/fem/flow/flow_source_assembly.hpp"

namespace moreau {

namespace {

constexpr int kMaxFields = 4;
constexpr int kMaxCellDofs = kMaxFields * kMaxElementNodes;
using CellVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxCellDofs, 1>;
using CellMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCellDofs, kMaxCellDofs>;

// The SUPG/PSPG parameter at a point, tau = (s^2 + (2/dt)^2 + (4 nu / h^2)^2)^-1/2, with
// s = sum_a |u . grad N_a| the advective rate (1/s), h the cell's size (m), nu the kinematic
// viscosity (m^2/s) and 1/dt (0 when steady).
Real stabilization_tau(Real advective_rate, Real h, Real nu, Real inverse_dt) {
  return 1 / std::sqrt(advective_rate * advective_rate + 4 * inverse_dt * inverse_dt + std::pow(4 * nu / (h * h), 2));
}

// The time scheme's coefficients (navier_stokes.hpp): du/dt = (a0 u_{n+1} + a1 u_n + a2 u_{n-1}) * ct,
// momentum terms at theta u_{n+1} + (1 - theta) u_n.
struct SchemeCoefficients {
  Real a0 = 0, a1 = 0, a2 = 0, theta = 1, ct = 0;
};

SchemeCoefficients scheme_coefficients(const FlowTimeStep& step) {
  if (!step.transient()) return {};
  const Real ct = 1 / step.dt;
  switch (step.integrator) {
    case FlowIntegrator::bdf2: return {1.5, -2, 0.5, 1, ct};
    case FlowIntegrator::midpoint: return {1, -1, 0, 0.5, ct};
    default: return {1, -1, 0, 1, ct};
  }
}

// The residual and the Jacobian (tau frozen; `picard`: advecting velocity frozen too) of one
// cell; local dofs node-major, fields (velocity components, pressure). x: u_{n+1}, x1: u_n, x2:
// u_{n-1} (null when their coefficients vanish). f: the sources' force density at the nodes
// (null: none), which the stabilization's strong residual includes; S (with the Jacobian, if f is
// given): the residual's derivative in f.
void flow_cell(const NavierStokesModel& m, Index e, const Real* x, const Real* x1, const Real* x2, const Real* f,
               const SchemeCoefficients& c, bool with_jacobian, bool picard, Real mu, CellVector& R, CellMatrix& J,
               CellMatrix& S) {
  const int dim = m.dim(), F = m.fields(), nodes = m.mesh.nodes_per_cell(), n = F * nodes;
  const Real rho = m.density, nu = mu / rho, theta = c.theta;
  R.setZero(n);
  if (with_jacobian) J.setZero(n, n);
  if (with_jacobian && f) S.setZero(n, n);
  const Real h = m.cell_size[e];
  Real adv[kMaxElementNodes];
  for (int q = 0; q < m.points; ++q) {
    const size_t qp = static_cast<size_t>(e) * m.points + q;
    const Real w = m.weight[qp];
    const Real* N = m.shape.data() + qp * nodes;
    const Vec3* dN = m.gradient.data() + qp * nodes;
    // u, G (G_ij = du_i/dx_j) and div u at theta; ut the time derivative; p and grad p the
    // unknown pressure (at t_{n+theta}).
    Vec3 u = Vec3::Zero(), ut = Vec3::Zero(), gp = Vec3::Zero();
    Mat3 G = Mat3::Zero();
    Real p = 0, div = 0;
    for (int a = 0; a < nodes; ++a) {
      for (int i = 0; i < dim; ++i) {
        const Real now = x[a * F + i], before = x1 ? x1[a * F + i] : 0, older = x2 ? x2[a * F + i] : 0;
        const Real at_theta = theta * now + (1 - theta) * before;
        u[i] += N[a] * at_theta;
        ut[i] += N[a] * c.ct * (c.a0 * now + c.a1 * before + c.a2 * older);
        G.row(i) += at_theta * dN[a].transpose();
        div += at_theta * dN[a][i];
      }
      p += N[a] * x[a * F + dim];
      gp += x[a * F + dim] * dN[a];
    }
    // Strong momentum residual (gradients have zero components past dim, so 3-vector dot
    // products below are the dim-dimensional ones). The stabilization's, rs, also has the
    // sources' force density f_h = sum_a N_a f_a: where an immersed body holds the fluid, rs is the
    // small residual of the whole balance, not the large force that holds it (without f_h, PSPG
    // would read that force as a pressure-gradient error and let the fluid through the body).
    const Vec3 r = rho * (ut + G * u - m.body_force) + gp;
    Vec3 rs = r;
    if (f)
      for (int a = 0; a < nodes; ++a)
        for (int i = 0; i < dim; ++i) rs[i] -= N[a] * f[a * F + i];
    Real s1 = 0;
    for (int a = 0; a < nodes; ++a) {
      adv[a] = u.dot(dN[a]);
      s1 += std::abs(adv[a]);
    }
    // tau = (tau1^-2 + tau2^-2 + tau3^-2)^-1/2 with tau1^-1 = sum_a |u . grad N_a|, tau2 = dt/2
    // (transient only: ct = 1/dt, 0 when steady), tau3 = h^2 / (4 nu).
    const Real tau = m.fixed_tau > 0 ? m.fixed_tau : stabilization_tau(s1, h, nu, c.ct);
    const Real nu_lsic = m.fixed_tau > 0 ? m.fixed_lsic : tau * u.squaredNorm();
    for (int a = 0; a < nodes; ++a) {
      for (int i = 0; i < dim; ++i) {
        Real viscous = 0;
        for (int k = 0; k < dim; ++k) viscous += (G(i, k) + G(k, i)) * dN[a][k];
        R[a * F + i] += w * (N[a] * (r[i] - gp[i]) + mu * viscous - p * dN[a][i] + tau * adv[a] * rs[i] +
                             nu_lsic * rho * dN[a][i] * div);
      }
      R[a * F + dim] += w * (N[a] * div + tau / rho * dN[a].dot(rs));
    }
    if (!with_jacobian) continue;
    if (f)  // d rs / d f_bj = -N_b e_j
      for (int a = 0; a < nodes; ++a)
        for (int b = 0; b < nodes; ++b)
          for (int j = 0; j < dim; ++j) {
            S(a * F + j, b * F + j) -= w * tau * adv[a] * N[b];
            S(a * F + dim, b * F + j) -= w * tau / rho * dN[a][j] * N[b];
          }
    // Newton: d u_theta / d u_{n+1} = theta, d ut / d u_{n+1} = a0 / dt. Picard drops the
    // derivatives through the advecting velocity (the G N_b term and the SUPG test function's).
    const Real frozen = picard ? 0 : 1;
    for (int a = 0; a < nodes; ++a)
      for (int b = 0; b < nodes; ++b) {
        const Real mass_adv = c.a0 * c.ct * N[b] + theta * adv[b];
        const Real grad_dot = dN[a].dot(dN[b]);
        for (int j = 0; j < dim; ++j) {
          // d r_i / d u_bj = rho ((a0 N_b / dt + theta u . grad N_b) delta_ij + theta G_ij N_b)
          Vec3 dr = frozen * theta * rho * G.col(j) * N[b];
          dr[j] += rho * mass_adv;
          for (int i = 0; i < dim; ++i) {
            Real v = N[a] * dr[i] + theta * mu * ((i == j ? grad_dot : 0) + dN[a][j] * dN[b][i]) + tau * adv[a] * dr[i] +
                     frozen * theta * tau * N[b] * dN[a][j] * rs[i] + theta * nu_lsic * rho * dN[a][i] * dN[b][j];
            J(a * F + i, b * F + j) += w * v;
          }
          J(a * F + dim, b * F + j) += w * (theta * N[a] * dN[b][j] + tau / rho * dN[a].dot(dr));
        }
        for (int i = 0; i < dim; ++i) J(a * F + i, b * F + dim) += w * (-dN[a][i] * N[b] + tau * adv[a] * dN[b][i]);
        J(a * F + dim, b * F + dim) += w * tau / rho * grad_dot;
      }
  }
}

}  // namespace

void assemble_flow(const NavierStokesModel& m, const VectorX& x, const FlowTimeStep& step, VectorX& R, SparseMatrix* J,
                   const FlowAssembly& how, const FlowForceDensity& density) {
  const Real mu = how.viscosity > 0 ? how.viscosity : m.viscosity;
  const int F = m.fields(), nodes = m.mesh.nodes_per_cell(), n = F * nodes;
  const SchemeCoefficients coefficients = scheme_coefficients(step);
  if (step.transient() && !(step.dt > 0)) throw std::invalid_argument("assemble_flow: a transient step needs dt > 0");
  if (step.transient() && !step.previous) throw std::invalid_argument("assemble_flow: a transient step needs x_n");
  if (coefficients.a2 != 0 && !step.before_previous) throw std::invalid_argument("assemble_flow: BDF2 needs x_{n-1}");
  const VectorX* x1 = step.transient() ? step.previous : nullptr;
  const VectorX* x2 = coefficients.a2 != 0 ? step.before_previous : nullptr;
  R.setZero(m.dof_count());
  const VectorX* f = density.values;
  SparseMatrix* S = J && f ? density.jacobian : nullptr;
  for (SparseMatrix* matrix : {J, S})
    if (matrix) {
      *matrix = m.pattern;
      std::fill(matrix->valuePtr(), matrix->valuePtr() + matrix->nonZeros(), 0.0);
    }
  const bool own_rows_only = how.own_rows_only && m.partition;
  for_each_cell_by_colour(own_rows_only ? m.partition->colours : m.colours, how.threads, [&](Index e) {
    CellVector Re;
    CellMatrix Je, Se;
    Real local[kMaxCellDofs], local1[kMaxCellDofs], local2[kMaxCellDofs], local_f[kMaxCellDofs];
    const Index* cell = m.mesh.cell(e);
    for (int a = 0; a < nodes; ++a)
      for (int k = 0; k < F; ++k) {
        const Index d = m.dof(cell[a], k);
        local[a * F + k] = x[d];
        if (x1) local1[a * F + k] = (*x1)[d];
        if (x2) local2[a * F + k] = (*x2)[d];
        if (f) local_f[a * F + k] = (*f)[d];
      }
    flow_cell(m, e, local, x1 ? local1 : nullptr, x2 ? local2 : nullptr, f ? local_f : nullptr, coefficients, J != nullptr,
              how.picard, mu, Re, Je, Se);
    for (int a = 0; a < nodes; ++a)
      for (int k = 0; k < F; ++k) R[m.dof(cell[a], k)] += Re[a * F + k];
    if (!J) return;
    const Index* slots = m.slots.data() + static_cast<size_t>(e) * n * n;
    for (int r = 0; r < n; ++r)
      for (int q = 0; q < n; ++q)
        if (slots[r * n + q] >= 0) {
          J->valuePtr()[slots[r * n + q]] += Je(r, q);
          if (S) S->valuePtr()[slots[r * n + q]] += Se(r, q);
        }
  });
}


void setup_navier_stokes(NavierStokesModel& m, const petsc_plugin::Communicator* ranks) {
  FemMesh& mesh = m.mesh;
  if (mesh.element != ElementType::quad4 && mesh.element != ElementType::hex8)
    throw InputError(fmt::format("the flow solver uses quad4 (2D) or hex8 (3D) cells, not {}", element_name(mesh.element)));
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
        for (int k = m.dim(); k < 3; ++k) g[k] = 0;
        m.gradient[qp * nodes + a] = g;
      }
    }
    m.cell_size[e] = std::pow(measure, 1.0 / m.dim());
  }
  m.node_volume.assign(mesh.node_count(), 0);
  for (Index e = 0; e < mesh.cell_count(); ++e)
    for (int q = 0; q < m.points; ++q) {
      const size_t qp = static_cast<size_t>(e) * m.points + q;
      for (int a = 0; a < nodes; ++a) m.node_volume[mesh.cell(e)[a]] += m.weight[qp] * m.shape[qp * nodes + a];
    }
  m.colours = colour_cells(mesh);
  m.free_count = number_free_dofs(m.dof_count(), m.prescribed, m.free_index);
  m.partition.reset();
  std::vector<char> kept_rows;  // distributed: this rank's
  if (ranks && ranks->size() > 1) {
    auto partition = std::make_shared<FlowPartition>();
    const std::vector<int> node_owner = partition_nodes({{&mesh, 0}}, mesh.node_count(), ranks->size());
    partition->rows = own_rows_by_node(node_owner, m.free_index, F, m.free_count, *ranks);
    partition->colours = cells_of_rank(m.colours, {&mesh, 0}, node_owner, ranks->rank());
    for (const std::vector<Index>& colour : partition->colours) partition->cells += static_cast<Index>(colour.size());
    kept_rows.resize(m.free_count);
    for (Index row = 0; row < m.free_count; ++row) kept_rows[row] = partition->rows.owns(row);
    m.partition = std::move(partition);
  }
  m.pattern = cell_coupling_pattern({{&mesh, 0}}, mesh.node_count(), F, m.free_index, m.free_count, kept_rows);
  m.slots = cell_slots(mesh, 0, F, m.free_index, m.pattern);
}

namespace {

// Newton's (or Picard's) iteration for one solve: unknowns the free dofs of x; converged when
// |R| <= stop * |R_0| (R_0 the residual at the start of this iteration).
struct FlowIterate {
  VectorX x, R;    // the solution and the residual on its free dofs
  SparseMatrix J;  // the Jacobian there, but for
  FlowLowRank low_rank;  // a source's low-rank part
};

class FlowSystem final : public NewtonIterates<FlowIterate> {
 public:
  FlowSystem(const NavierStokesModel& m, const FlowTimeStep& step, const VectorX& x, FlowLinearSolver& solver,
             const FlowAssembly& how, Real stop, NewtonResult& result, const FlowSource* source)
      : m_(m), step_(step), solver_(solver), how_(how), stop_(stop), result_(result), source_(source) {
    now_.x = x;
  }

  NewtonEvaluation evaluate(const VectorX* dx, Real alpha) override {
    if (!dx) {
      assemble(now_);
      first_ = std::max(now_.R.norm(), Real(1e-300));
      return measure(now_.R);
    }
    trial_.x = now_.x;
    add_free(m_.free_index, alpha * *dx, trial_.x);
    assemble(trial_);
    return measure(trial_.R);
  }
  bool solve(VectorX& dx, std::string& failure) override {
    const VectorX rhs = -now_.R;
    if (!timed(result_.solve_s, [&] { return solver_.factorize(now_.J) && solver_.solve(rhs, dx) && add_low_rank(dx); })) {
      failure = solver_.failure().empty() ? "the low-rank update of the Jacobian is singular" : solver_.failure();
      return false;
    }
    return true;
  }
  Real relative_correction(const VectorX& dx, Real alpha) const override {
    return alpha * dx.norm() / std::max(gather_free(m_.free_index, m_.free_count, now_.x).norm(), Real(1e-300));
  }

  // dx = A^-1 b on entry; the solution of (A + U V^T) dx = b on return (FlowLowRank).
  bool add_low_rank(VectorX& dx) {
    const FlowLowRank& l = now_.low_rank;
    if (l.U.cols() == 0) return true;
    Eigen::MatrixXd Z(l.U.rows(), l.U.cols());
    for (Eigen::Index k = 0; k < l.U.cols(); ++k) {
      VectorX z;
      if (!solver_.solve(l.U.col(k), z)) return false;
      Z.col(k) = z;
    }
    const Eigen::MatrixXd S = Eigen::MatrixXd::Identity(l.U.cols(), l.U.cols()) + l.V.transpose() * Z;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(S);
    dx -= Z * lu.solve(l.V.transpose() * dx);
    return dx.allFinite();
  }

  const VectorX& solution() const { return now_.x; }
  /// Wall time spent in the source's terms (part of the assembly time).
  double source_s() const { return source_s_; }

 private:
  // The residual on the free dofs and the Jacobian at the iterate's x.
  void assemble(FlowIterate& at) {
    const VectorX& x = at.x;
    SparseMatrix& J = at.J;
    VectorX full;
    at.low_rank = {};
    timed(result_.assembly_s, [&] {
      if (source_) assemble_flow_with_source(m_, x, step_, *source_, how_, full, &J, &at.low_rank, source_s_);
      else assemble_flow(m_, x, step_, full, &J, how_);
      return 0;
    });
    at.R = gather_free(m_.free_index, m_.free_count, full);
    if (m_.partition) timed(result_.assembly_s, [&] {
        m_.partition->rows.complete(at.R);
        return 0;
      });
  }
  NewtonEvaluation measure(const VectorX& R) const {
    NewtonEvaluation e;
    e.norm = R.norm();
    // A residual that is not finite (a solid node left the mesh) never counts as converged, even
    // when the first one was not finite either.
    e.converged = std::isfinite(e.norm) && (e.norm <= stop_ * first_ || e.norm == 0);
    e.relative = e.norm / first_;
    e.describe = fmt::format("|R| = {:.3e}, first {:.3e}", e.norm, first_);
    if (!std::isfinite(e.norm) && source_) {
      e.not_finite = source_->last_failure();
      if (!e.not_finite.empty()) e.describe += ": " + e.not_finite;
    }
    return e;
  }

  const NavierStokesModel& m_;
  const FlowTimeStep& step_;
  FlowLinearSolver& solver_;
  FlowAssembly how_;
  Real stop_;
  NewtonResult& result_;
  const FlowSource* source_;
  double source_s_ = 0;
  Real first_ = 1;
};

}  // namespace

FlowSolveResult solve_navier_stokes(const NavierStokesModel& m, Real t, const FlowTimeStep& step, VectorX& x,
                                    FlowLinearSolver& solver, const FlowSolveSettings& settings, const FlowSource* source) {
  FlowSolveResult result;
  for (const PrescribedDof& p : m.prescribed) x[p.dof] = p.value(t);
  solver.set_layout(m.free_index, m.fields(), m.free_count, m.partition ? &m.partition->rows.owner : nullptr);
  const VectorX start = x;
  NewtonSettings newton;
  newton.tolerance = settings.tolerance;
  newton.max_iterations = settings.max_iterations;
  newton.threads = settings.threads;
  const bool distributed = m.partition != nullptr;
  const FlowAssembly how{false, distributed, settings.viscosity, settings.threads};
  {
    FlowSystem system(m, step, x, solver, how, settings.tolerance, result, source);
    const bool converged = newton_solve(system, newton, "Newton's method", result);
    x = system.solution();
    result.source_s += system.source_s();
    if (converged) {
      result.converged = true;
      return result;
    }
  }
  if (!settings.picard_fallback) return result;
  // Picard from the same start (robust, linearly convergent), then Newton from where it got.
  const std::string newton_failure = result.failure;
  x = start;
  NewtonResult picard;
  NewtonSettings picard_settings = newton;
  picard_settings.max_iterations = settings.max_picard_iterations;
  picard_settings.line_search = false;  // Picard's direction need not decrease |R|
  FlowSystem picard_system(m, step, x, solver, {true, distributed, settings.viscosity, settings.threads}, settings.picard_reduction, picard, source);
  const bool picard_converged = newton_solve(picard_system, picard_settings, "Picard's iteration", picard);
  x = picard_system.solution();
  result.picard_iterations += picard.iterations;
  result.assembly_s += picard.assembly_s;
  result.solve_s += picard.solve_s;
  result.source_s += picard_system.source_s();
  result.residual_norms.insert(result.residual_norms.end(), picard.residual_norms.begin(), picard.residual_norms.end());
  result.failure = picard.failure;
  if (picard_converged) {
    // Newton again, to the tolerance relative to the first residual of the solve.
    const Real stop = settings.tolerance * picard.residual_norms.front() / std::max(picard.residual_norms.back(), Real(1e-300));
    FlowSystem system(m, step, x, solver, how, stop, result, source);
    const bool converged = newton_solve(system, newton, "Newton's method after Picard's", result);
    x = system.solution();
    result.source_s += system.source_s();
    if (converged) {
      result.converged = true;
      return result;
    }
  }
  result.failure = fmt::format("Newton failed ({}), and so did the Picard fallback: {}", newton_failure, result.failure);
  return result;
}

Real interpolate_flow_component(const NavierStokesModel& m, const MeshPoint& at, const VectorX& x, int k) {
  const Index* c = m.mesh.cell(at.cell);
  Real value = 0;
  for (int a = 0; a < m.mesh.nodes_per_cell(); ++a) value += at.shape[a] * x[m.dof(c[a], k)];
  return value;
}

void interpolate_flow(const NavierStokesModel& m, const MeshPoint& at, const VectorX& x, Vec3& velocity, Real& pressure) {
  velocity.setZero();
  for (int k = 0; k < m.dim(); ++k) velocity[k] = interpolate_flow_component(m, at, x, k);
  pressure = interpolate_flow_component(m, at, x, m.dim());
}

}  // namespace moreau
