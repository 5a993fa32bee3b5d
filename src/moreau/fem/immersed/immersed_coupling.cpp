#include "moreau/fem/immersed/immersed_coupling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "moreau/errors.hpp"

namespace moreau {

namespace {

// theta of the fluid's scheme: the time level of the momentum terms.
Real scheme_theta(const FlowTimeStep& step) {
  switch (step.integrator) {
    case FlowIntegrator::midpoint: return 0.5;
    case FlowIntegrator::backward_euler: return 1;
    default: throw std::logic_error("immersed solids need the midpoint rule or backward Euler");
  }
}

// The cell's solid dofs gathered node-major (dim per node) from a vector over all solid dofs.
void gather_cell(const FemModel& model, const FemSolid& solid, Index e, const VectorX& all, Real* local) {
  const Index* cell = solid.mesh.cell(e);
  for (int a = 0; a < solid.mesh.nodes_per_cell(); ++a)
    for (int k = 0; k < model.dim; ++k) local[a * model.dim + k] = all[model.dof(solid.node_begin + cell[a], k)];
}

// The mass of rho_s - rho_f between two of a cell's nodes (the solid's consistent mass rescaled).
Real excess_mass(const FemSolid& solid, Real fluid_density, Index e, int a, int b) {
  const int nodes = solid.mesh.nodes_per_cell();
  const Real scale = (solid.material.density - fluid_density) / solid.material.density;
  return scale * solid.cell_mass[static_cast<size_t>(e) * nodes * nodes + a * nodes + b];
}

// Adds the viscous force of the stress 2 mu d(V) at the cell's configuration u (Kelvin-Voigt) and,
// if K is given, scale times its derivative in V (F frozen):
//   f_a = int J sigma g_a dV,  g_a = F^-T grad_X N_a,  sigma = mu (L + L^T),  L = sum_b V_b (x) g_b,
//   d f_ai / d V_bj = int J mu (delta_ij g_a . g_b + g_aj g_bi).
bool add_viscous_force(const FemSolid& solid, Index e, int dim, Real mu, const Real* u, const Real* V, ElementVector& f,
                       ElementMatrix* K, Real scale) {
  const CellQuadrature q = solid.cell_quadrature(e);
  Vec3 g[kMaxElementNodes];
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Mat3 F = Mat3::Identity() + displacement_gradient(G, q.nodes, dim, u);
    const Real J = F.determinant();
    if (!(J > 0)) return false;
    const Mat3 F_inv_t = F.inverse().transpose();
    Mat3 L = Mat3::Zero();
    for (int a = 0; a < q.nodes; ++a) {
      g[a] = F_inv_t * G[a];
      for (int k = dim; k < 3; ++k) g[a][k] = 0;
      for (int k = 0; k < dim; ++k) L.row(k) += V[a * dim + k] * g[a].transpose();
    }
    const Real wJ = q.weight[p] * J;
    const Mat3 sigma = mu * (L + L.transpose());
    for (int a = 0; a < q.nodes; ++a) {
      const Vec3 t = sigma * g[a];
      for (int i = 0; i < dim; ++i) f[a * dim + i] += wJ * t[i];
      if (!K) continue;
      for (int b = 0; b < q.nodes; ++b) {
        const Real gg = g[a].dot(g[b]);
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            (*K)(a * dim + i, b * dim + j) += scale * wJ * mu * ((i == j ? gg : 0) + g[a][j] * g[b][i]);
      }
    }
  }
  return true;
}

}  // namespace

ImmersedCoupling::ImmersedCoupling(const NavierStokesModel& fluid, const ImmersedSolids& solids, ImmersedSolidState& state)
    : fluid_(fluid), solids_(solids), state_(state), locator_(fluid.mesh), rigid_(fluid, solids, locator_),
      rigid_node_(solids.model.node_count, 0) {
  if (solids.model.dim != fluid.dim()) throw std::logic_error("immersed solids and the fluid differ in dimension");
  if (state.fluid_force.size() != solids.model.solids.size() || state.frame.size() != solids.rigid_bodies.size())
    throw std::logic_error("the immersed state is not these solids' (start it with initial_immersed_state)");
  for (const ImmersedRigidBody& body : solids.rigid_bodies) {
    const FemSolid& solid = solids.model.solids[body.solid];
    std::fill_n(rigid_node_.begin() + solid.node_begin, solid.mesh.node_count(), 1);
  }
}

ImmersedKinematics ImmersedCoupling::kinematics(const VectorX& x, const FlowTimeStep& step) const {
  const FemModel& model = solids_.model;
  const int dim = model.dim;
  const Real theta = scheme_theta(step), dt = step.dt, t_next = state_.time + dt;
  const VectorX& x_n = *step.previous;
  ImmersedKinematics k;
  k.displacement = state_.displacement;
  k.velocity = state_.velocity;
  k.velocity_theta = state_.velocity;
  k.located.assign(model.node_count, MeshPoint{});
  // Prescribed components follow their own law; they need no fluid.
  std::vector<char> prescribed(model.dof_count(), 0);
  for (const PrescribedDof& p : model.prescribed) {
    prescribed[p.dof] = 1;
    const Real du = p.value(t_next) - state_.displacement[p.dof];
    k.displacement[p.dof] = p.value(t_next);
    k.velocity[p.dof] = k.velocity_theta[p.dof] = du / dt;
  }
  // x* = X + u_n + theta dt V_theta, with V_theta = M(x*) v_theta: a fixed point, started from
  // the solid's own velocity at t_n.
  const Real smallest_cell = *std::min_element(fluid_.cell_size.begin(), fluid_.cell_size.end());
  const Real tolerance = 1e-12 * smallest_cell;
  std::vector<Vec3> x_star(model.node_count);
  for (Index n = 0; n < model.node_count; ++n) {
    x_star[n] = model.reference_position(n);
    for (int c = 0; c < dim; ++c) {
      const Index d = model.dof(n, c);
      x_star[n][c] += state_.displacement[d] + theta * dt * k.velocity_theta[d];
    }
  }
  // A node whose every component is prescribed (clamped) follows its law alone: it need not lie
  // in the fluid (a base on a curved wall may sit just outside the fluid's polygonal boundary).
  std::vector<char> held(model.node_count, 1);
  for (Index n = 0; n < model.node_count; ++n)
    for (int c = 0; c < dim; ++c) held[n] = held[n] && prescribed[model.dof(n, c)];
  for (int it = 0; it < 50; ++it) {
    Real change = 0;
    for (Index n = 0; n < model.node_count; ++n) {
      if (held[n] || rigid_node_[n]) continue;
      const std::optional<MeshPoint> at = locator_.locate(x_star[n], k.located[n].cell);
      if (!at) {
        const auto [solid, local] = model.owner(n);
        throw NumericalError(fmt::format("immersed solid '{}': node {} at ({:.6g}, {:.6g}, {:.6g}) m left the fluid's mesh",
                                         solid->name, local, x_star[n].x(), x_star[n].y(), x_star[n].z()));
      }
      k.located[n] = *at;
      Vec3 moved = model.reference_position(n);
      for (int c = 0; c < dim; ++c) {
        const Index d = model.dof(n, c);
        if (!prescribed[d]) {
          const Real v_next = interpolate_flow_component(fluid_, *at, x, c),
                     v_before = interpolate_flow_component(fluid_, *at, x_n, c);
          k.velocity[d] = v_next;
          k.velocity_theta[d] = theta * v_next + (1 - theta) * v_before;
          k.displacement[d] = state_.displacement[d] + dt * k.velocity_theta[d];
        }
        moved[c] += state_.displacement[d] + theta * (k.displacement[d] - state_.displacement[d]);
      }
      change = std::max(change, (moved - x_star[n]).cwiseAbs().maxCoeff());
      x_star[n] = moved;
    }
    if (change <= tolerance) break;
  }
  return k;
}

SparseMatrix ImmersedCoupling::velocity_map(const ImmersedKinematics& k, bool free_columns) const {
  const FemModel& model = solids_.model;
  std::vector<Eigen::Triplet<Real, int>> entries;
  for (Index n = 0; n < model.node_count; ++n) {
    const MeshPoint& at = k.located[n];
    if (at.cell < 0) continue;  // a clamped node, or a rigid body's
    for (int i = 0; i < model.dim; ++i) {
      const Index row = model.dof(n, i);
      if (model.free_index[row] < 0) continue;
      const Index* cell = fluid_.mesh.cell(at.cell);
      for (int a = 0; a < fluid_.mesh.nodes_per_cell(); ++a) {
        const Index dof = fluid_.dof(cell[a], i), column = free_columns ? fluid_.free_index[dof] : dof;
        if (column >= 0 && at.shape[a] != 0) entries.emplace_back(static_cast<int>(row), static_cast<int>(column), at.shape[a]);
      }
    }
  }
  SparseMatrix M(model.dof_count(), free_columns ? fluid_.free_count : fluid_.dof_count());
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

// The deformable solids' nodal forces r (per solid dof) at the kinematics k and, if asked, their
// per-cell derivatives gathered over the solid's dofs: d r / d V_theta (elastic through
// u_n+1 = u_n + dt V_theta, and viscous) and d r / d V_n+1 (the excess inertia). False if a solid
// cell is inverted.
bool ImmersedCoupling::nodal_forces(const ImmersedKinematics& k, Real theta, Real dt, VectorX& r,
                                    std::vector<Eigen::Triplet<Real, int>>* by_theta_velocity,
                                    std::vector<Eigen::Triplet<Real, int>>* by_next_velocity) const {
  const FemModel& model = solids_.model;
  const int dim = model.dim;
  const bool with_jacobian = by_theta_velocity != nullptr;
  const VectorX u_theta = state_.displacement + theta * (k.displacement - state_.displacement);
  r = VectorX::Zero(model.dof_count());
  for (size_t s = 0; s < model.solids.size(); ++s) {
    if (solids_.rigid_body_of(s)) continue;
    const FemSolid& solid = model.solids[s];
    const int nodes = solid.mesh.nodes_per_cell();
    const Real viscosity_difference = solids_.viscosity[s] - fluid_.viscosity;
    for (Index e = 0; e < solid.mesh.cell_count(); ++e) {
      Real u_n[kMaxElementDofs], u_next[kMaxElementDofs], u_mid[kMaxElementDofs], V[kMaxElementDofs],
          V_next[kMaxElementDofs], V_n[kMaxElementDofs];
      gather_cell(model, solid, e, state_.displacement, u_n);
      gather_cell(model, solid, e, k.displacement, u_next);
      gather_cell(model, solid, e, u_theta, u_mid);
      gather_cell(model, solid, e, k.velocity_theta, V);
      gather_cell(model, solid, e, k.velocity, V_next);
      gather_cell(model, solid, e, state_.velocity, V_n);
      // Elastic: the discrete gradient (midpoint rule) or the force at u_n+1 (backward Euler);
      // its tangent is d f / d u_n+1, and d u_n+1 / d V_theta = dt.
      ElementOutput out;
      if (theta == 1)
        solid_element(solid.material, solid.volume, solid.cell_quadrature(e), dim, u_next, with_jacobian, out);
      else
        solid_element_step(solid.material, solid.volume, solid.cell_quadrature(e), dim, u_n, u_next, StepRule::energy_momentum,
                           with_jacobian, out);
      ElementMatrix K_theta, K_next;
      if (with_jacobian) {
        K_theta = dt * out.tangent;
        K_next.setZero(out.tangent.rows(), out.tangent.cols());
      }
      bool valid = out.valid;
      if (valid && viscosity_difference != 0)
        valid = add_viscous_force(solid, e, dim, viscosity_difference, u_mid, V, out.force, with_jacobian ? &K_theta : nullptr, 1);
      if (!valid) return false;
      const Vec3 b = fluid_.body_force;
      for (int a = 0; a < nodes; ++a)
        for (int c = 0; c < nodes; ++c) {
          const Real m = excess_mass(solid, fluid_.density, e, a, c);
          if (m == 0) continue;
          for (int i = 0; i < dim; ++i) {
            out.force[a * dim + i] += m * ((V_next[c * dim + i] - V_n[c * dim + i]) / dt - b[i]);
            if (with_jacobian) K_next(a * dim + i, c * dim + i) += m / dt;
          }
        }
      const Index* cell = solid.mesh.cell(e);
      auto dof = [&](int a, int i) { return static_cast<int>(model.dof(solid.node_begin + cell[a], i)); };
      for (int a = 0; a < nodes; ++a)
        for (int i = 0; i < dim; ++i) {
          r[dof(a, i)] += out.force[a * dim + i];
          if (!with_jacobian) continue;
          for (int c = 0; c < nodes; ++c)
            for (int j = 0; j < dim; ++j) {
              const int row = a * dim + i, column = c * dim + j;
              if (K_theta(row, column) != 0) by_theta_velocity->emplace_back(dof(a, i), dof(c, j), K_theta(row, column));
              if (K_next(row, column) != 0) by_next_velocity->emplace_back(dof(a, i), dof(c, j), K_next(row, column));
            }
        }
    }
  }
  return true;
}

void ImmersedCoupling::add(const VectorX& x, const FlowTimeStep& step, VectorX& R,
                           std::vector<Eigen::Triplet<Real, int>>* jacobian, FlowLowRank* low_rank) const {
  const Real theta = scheme_theta(step), dt = step.dt;
  last_failure_.clear();
  ImmersedKinematics k;
  try {
    k = kinematics(x, step);
  } catch (const NumericalError& e) {
    // A trial iterate that carries a solid node out of the fluid: an infinite residual makes
    // Newton's line search shorten the step (a converged step that does so fails in accept()).
    last_failure_ = e.what();
    R.setConstant(std::numeric_limits<Real>::infinity());
    return;
  }
  VectorX r;
  std::vector<Eigen::Triplet<Real, int>> by_theta_velocity, by_next_velocity;
  if (!nodal_forces(k, theta, dt, r, jacobian ? &by_theta_velocity : nullptr, jacobian ? &by_next_velocity : nullptr)) {
    // An inverted solid cell: an infinite residual makes Newton's line search shorten the step.
    R.setConstant(std::numeric_limits<Real>::infinity());
    return;
  }
  // R += M^T r (prescribed components' rows of M are empty: their forces are reactions).
  R += velocity_map(k, false).transpose() * r;
  if (jacobian) add_jacobian(k, x, *step.previous, theta, dt, r, by_theta_velocity, by_next_velocity, *jacobian);
  if (!solids_.rigid_bodies.empty()) {
    last_failure_ = rigid_.add(x, step, theta, state_, R, jacobian, low_rank);
    if (!last_failure_.empty()) R.setConstant(std::numeric_limits<Real>::infinity());  // as for a node leaving the mesh
  }
}

// The mapped velocities' derivatives in the fluid's velocities v = v_n+1 (free dofs), with the
// motion of the solid's nodes inside the fluid's cells included. Per solid node C, with
// G = grad v at x*_C (G_ij = sum_A v_Ai dN_A/dx_j) and M_C its rows of M:
//   V_theta = M(x*) v_theta,  x* = X + u_n + theta dt V_theta
//     => dV_theta = theta M_C dv + G_theta dx*,  dx* = theta dt dV_theta
//     => dV_theta / dv = D_C = theta (I - theta dt G_theta)^-1 M_C,   dx* / dv = theta dt D_C,
//   dV_n+1 / dv = M_C + theta dt G_n+1 D_C,
// and the spread force R_Ai = sum_C N_A(x*_C) r_Ci adds r_Ci grad N_A(x*_C) . dx*_C. Prescribed
// components follow their law: their rows of G, M and D vanish, and their r (a reaction) is not
// spread. So
//   J += M^T (K_theta D + K_next (M + theta dt G_n+1 D)) + theta dt E D,
//   E_(Ai),(Cj) = r_Ci dN_A/dx_j (x*_C),
// exact but for the viscous difference's dependence on the displacement (its F is frozen).
void ImmersedCoupling::add_jacobian(const ImmersedKinematics& k, const VectorX& x, const VectorX& x_n, Real theta, Real dt,
                                    const VectorX& r, const std::vector<Eigen::Triplet<Real, int>>& by_theta_velocity,
                                    const std::vector<Eigen::Triplet<Real, int>>& by_next_velocity,
                                    std::vector<Eigen::Triplet<Real, int>>& jacobian) const {
  const FemModel& model = solids_.model;
  const int dim = model.dim, nodes_per_cell = fluid_.mesh.nodes_per_cell();
  const Index solid_dofs = model.dof_count();
  const Real theta_dt = theta * dt;
  std::vector<Eigen::Triplet<Real, int>> moved_entries, gradient_entries, spread_entries;
  for (Index n = 0; n < model.node_count; ++n) {
    const MeshPoint& at = k.located[n];
    if (at.cell < 0) continue;
    const Index* cell = fluid_.mesh.cell(at.cell);
    Mat3 G_theta = Mat3::Zero(), G_next = Mat3::Zero();
    for (int i = 0; i < dim; ++i) {
      if (model.free_index[model.dof(n, i)] < 0) continue;
      for (int a = 0; a < nodes_per_cell; ++a) {
        const Real v_next = x[fluid_.dof(cell[a], i)], v_before = x_n[fluid_.dof(cell[a], i)];
        G_next.row(i) += v_next * at.gradient[a].transpose();
        G_theta.row(i) += (theta * v_next + (1 - theta) * v_before) * at.gradient[a].transpose();
      }
    }
    const Mat3 A = theta * (Mat3::Identity() - theta_dt * G_theta).inverse();
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) {
        const int row = static_cast<int>(model.dof(n, i)), column = static_cast<int>(model.dof(n, j));
        if (A(i, j) != 0) moved_entries.emplace_back(row, column, A(i, j));
        if (G_next(i, j) != 0) gradient_entries.emplace_back(row, column, theta_dt * G_next(i, j));
      }
    for (int i = 0; i < dim; ++i) {
      const Index solid_dof = model.dof(n, i);
      if (model.free_index[solid_dof] < 0 || r[solid_dof] == 0) continue;
      for (int a = 0; a < nodes_per_cell; ++a) {
        const Index fluid_row = fluid_.free_index[fluid_.dof(cell[a], i)];
        if (fluid_row < 0) continue;
        for (int j = 0; j < dim; ++j)
          if (at.gradient[a][j] != 0)
            spread_entries.emplace_back(static_cast<int>(fluid_row), static_cast<int>(model.dof(n, j)),
                                        theta_dt * r[solid_dof] * at.gradient[a][j]);
      }
    }
  }
  auto matrix = [](Index rows, Index columns, const std::vector<Eigen::Triplet<Real, int>>& entries) {
    SparseMatrix m(rows, columns);
    m.setFromTriplets(entries.begin(), entries.end());
    return m;
  };
  const SparseMatrix M = velocity_map(k, true);
  const SparseMatrix D = matrix(solid_dofs, solid_dofs, moved_entries) * M;
  const SparseMatrix next_velocity = M + matrix(solid_dofs, solid_dofs, gradient_entries) * D;
  const SparseMatrix force_change = matrix(solid_dofs, solid_dofs, by_theta_velocity) * D +
                                    matrix(solid_dofs, solid_dofs, by_next_velocity) * next_velocity;
  const SparseMatrix coupling = SparseMatrix(M.transpose()) * force_change +
                                matrix(fluid_.free_count, solid_dofs, spread_entries) * D;
  for (int column = 0; column < coupling.outerSize(); ++column)
    for (SparseMatrix::InnerIterator it(coupling, column); it; ++it) jacobian.emplace_back(it.row(), it.col(), it.value());
}

// The fluid's force on a deformable solid over a step, from the balance of the solid with the
// fluid it displaces: the solid's nodal forces r are what it applies to the fluid (its elastic and
// viscous forces and the inertia of rho_s - rho_f, spread by M^T); the fluid inside the solid
// (density rho_f, moving with it) adds its own inertia and weight, so the surrounding fluid's
// traction on the solid has the resultant
//   F = sum_C r_C + sum_C,D M^f_CD ((V_D,n+1 - V_D,n) / dt - b),
// over the solid's free components (a clamped base's forces are reactions of its support, not the
// fluid's). M^f is the consistent mass at the fluid's density. At rest in a steady flow F is the
// drag and lift the solid takes from the fluid: the sum of its forces on the fluid.
Vec3 ImmersedCoupling::fluid_force_on_solid(size_t s, const ImmersedKinematics& k, const VectorX& r, Real dt) const {
  const FemModel& model = solids_.model;
  const FemSolid& solid = model.solids[s];
  const int dim = model.dim, nodes = solid.mesh.nodes_per_cell();
  Vec3 force = Vec3::Zero();
  for (Index n = 0; n < solid.mesh.node_count(); ++n)
    for (int i = 0; i < dim; ++i) {
      const Index d = model.dof(solid.node_begin + n, i);
      if (model.free_index[d] >= 0) force[i] += r[d];
    }
  const Real fluid_share = fluid_.density / solid.material.density;
  for (Index e = 0; e < solid.mesh.cell_count(); ++e) {
    const Index* cell = solid.mesh.cell(e);
    for (int a = 0; a < nodes; ++a)
      for (int c = 0; c < nodes; ++c) {
        const Real m = fluid_share * solid.cell_mass[static_cast<size_t>(e) * nodes * nodes + a * nodes + c];
        for (int i = 0; i < dim; ++i) {
          const Index row = model.dof(solid.node_begin + cell[a], i), column = model.dof(solid.node_begin + cell[c], i);
          if (model.free_index[row] < 0) continue;
          force[i] += m * ((k.velocity[column] - state_.velocity[column]) / dt - fluid_.body_force[i]);
        }
      }
  }
  return force;
}

void ImmersedCoupling::accept(const VectorX& x, const FlowTimeStep& step) {
  const Real theta = scheme_theta(step);
  const ImmersedKinematics k = kinematics(x, step);
  // The step's loads, from the state it started from: the source's residual on the fluid (for the
  // walls' reactions; the same M^T r as add() puts in the residual) and the fluid's force on each
  // deformable solid (the rigid bodies' below).
  VectorX r;
  if (!nodal_forces(k, theta, step.dt, r, nullptr, nullptr)) throw NumericalError("an immersed solid's cell is inverted");
  state_.fluid_source = velocity_map(k, false).transpose() * r;
  if (!solids_.rigid_bodies.empty()) {
    const std::string failure = rigid_.add(x, step, theta, state_, state_.fluid_source, nullptr, nullptr);
    if (!failure.empty()) throw NumericalError(failure);
  }
  for (size_t s = 0; s < solids_.model.solids.size(); ++s)
    if (!solids_.rigid_body_of(s)) state_.fluid_force[s] = fluid_force_on_solid(s, k, r, step.dt);
  state_.displacement = k.displacement;
  state_.velocity = k.velocity;
  rigid_.accept(x, step, theta, state_);
  state_.time += step.dt;
}

Real immersed_elastic_energy(const ImmersedSolids& solids, const ImmersedSolidState& state) {
  const FemModel& model = solids.model;
  Real energy = 0;
  for (const FemSolid& solid : model.solids)
    for (Index e = 0; e < solid.mesh.cell_count(); ++e) {
      Real u[kMaxElementDofs];
      gather_cell(model, solid, e, state.displacement, u);
      ElementOutput out;
      solid_element(solid.material, solid.volume, solid.cell_quadrature(e), model.dim, u, false, out);
      energy += out.energy;
    }
  return energy;
}

Real immersed_excess_kinetic_energy(const ImmersedSolids& solids, const NavierStokesModel& fluid,
                                    const ImmersedSolidState& state) {
  const FemModel& model = solids.model;
  Real energy = 0;
  for (const FemSolid& solid : model.solids) {
    const int nodes = solid.mesh.nodes_per_cell();
    for (Index e = 0; e < solid.mesh.cell_count(); ++e) {
      Real V[kMaxElementDofs];
      gather_cell(model, solid, e, state.velocity, V);
      for (int a = 0; a < nodes; ++a)
        for (int b = 0; b < nodes; ++b)
          for (int i = 0; i < model.dim; ++i)
            energy += 0.5 * excess_mass(solid, fluid.density, e, a, b) * V[a * model.dim + i] * V[b * model.dim + i];
    }
  }
  return energy;
}

}  // namespace moreau
