#include "moreau/fem/immersed/immersed_rigid_body.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "moreau/errors.hpp"
#include "moreau/fem/immersed/prescribed_rigid_motion.hpp"

namespace moreau {

namespace {

using MatrixXd = Eigen::MatrixXd;

int rigid_frame_size(int dim) { return dim * (dim + 1); }
int rigid_constraint_count(int dim) { return dim * (dim + 1) / 2; }

// The weights of node C's map Q_C = [s_0 I, s_1 I, ..]: s_0 = 1 (phi), s_j = xi_j (director j).
std::array<Real, 4> rigid_node_weights(const Vec3& xi, int dim) {
  std::array<Real, 4> s{1, 0, 0, 0};
  for (int j = 0; j < dim; ++j) s[j + 1] = xi[j];
  return s;
}

// Q_C q: the point (or velocity) of node C.
Vec3 apply_rigid_node_map(const std::array<Real, 4>& s, const VectorX& q, int dim) {
  Vec3 x = Vec3::Zero();
  for (int block = 0; block <= dim; ++block)
    for (int k = 0; k < dim; ++k) x[k] += s[block] * q[block * dim + k];
  return x;
}

// The director d_i of a frame (i from 0).
Vec3 frame_director(const VectorX& q, int i, int dim) {
  Vec3 d = Vec3::Zero();
  for (int k = 0; k < dim; ++k) d[k] = q[(i + 1) * dim + k];
  return d;
}

// The internal constraints' pairs (i <= j): g_ij = d_i . d_j - delta_ij (halved on the diagonal,
// so that G is the plain derivative d_j on d_i and d_i on d_j).
std::vector<std::pair<int, int>> frame_constraint_pairs(int dim) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < dim; ++i) pairs.emplace_back(i, i);
  for (int i = 0; i < dim; ++i)
    for (int j = i + 1; j < dim; ++j) pairs.emplace_back(i, j);
  return pairs;
}

VectorX frame_constraints(const VectorX& q, int dim) {
  const auto pairs = frame_constraint_pairs(dim);
  VectorX g(pairs.size());
  for (size_t r = 0; r < pairs.size(); ++r) {
    const auto [i, j] = pairs[r];
    const Real dot = frame_director(q, i, dim).dot(frame_director(q, j, dim));
    g[r] = i == j ? (dot - 1) / 2 : dot;
  }
  return g;
}

MatrixXd frame_constraint_jacobian(const VectorX& q, int dim) {
  const auto pairs = frame_constraint_pairs(dim);
  MatrixXd G = MatrixXd::Zero(pairs.size(), rigid_frame_size(dim));
  for (size_t r = 0; r < pairs.size(); ++r) {
    const auto [i, j] = pairs[r];
    for (int k = 0; k < dim; ++k) {
      if (i == j) {
        G(r, (i + 1) * dim + k) = q[(i + 1) * dim + k];
      } else {
        G(r, (i + 1) * dim + k) = q[(j + 1) * dim + k];
        G(r, (j + 1) * dim + k) = q[(i + 1) * dim + k];
      }
    }
  }
  return G;
}

// A += scale sum_r mu_r Hess g_r: I on the director blocks (i, i) for the diagonal pairs, on
// (i, j) and (j, i) for the others.
void add_frame_constraint_hessian(const VectorX& mu, Real scale, int dim, MatrixXd& A) {
  const auto pairs = frame_constraint_pairs(dim);
  for (size_t r = 0; r < pairs.size(); ++r) {
    const auto [i, j] = pairs[r];
    for (int k = 0; k < dim; ++k) {
      A((i + 1) * dim + k, (j + 1) * dim + k) += scale * mu[r];
      if (i != j) A((j + 1) * dim + k, (i + 1) * dim + k) += scale * mu[r];
    }
  }
}

}  // namespace

// One body's frame for one evaluation: the solution of its equations and what the fluid's
// residual and Jacobian need of it.
struct ImmersedRigidCoupling::BodyStep {
  VectorX velocity;               // dq_n+1
  VectorX velocity_theta;         // dq_theta
  VectorX next;                   // q_n+1
  std::vector<MeshPoint> at;      // per node: where x_C(q_theta) lies in the fluid
  std::vector<Vec3> force;        // per node: lambda_C, N (2D: N/m), the fluid's pull on the body
  std::vector<Mat3> gradient;     // per node: grad v_theta at x_C
  MatrixXd jacobian;              // of the body's equations in (dq_n+1, mu)
};

VectorX rigid_frame_at_rest(const ImmersedRigidBody& body, int dim) {
  VectorX q = VectorX::Zero(rigid_frame_size(dim));
  for (int k = 0; k < dim; ++k) q[k] = body.centre[k];
  for (int i = 0; i < dim; ++i) q[(i + 1) * dim + i] = 1;
  return q;
}

ImmersedRigidBody make_immersed_rigid_body(const FemModel& model, Index solid_index, Real fluid_density,
                                           Real coupling_stiffness) {
  const FemSolid& solid = model.solids[solid_index];
  const int dim = model.dim, nodes = solid.mesh.nodes_per_cell();
  ImmersedRigidBody body;
  body.solid = solid_index;
  body.coupling_stiffness = coupling_stiffness;
  // Consistent mass per node pair, summed: the mass, its first moment (the centre) and the
  // nodal volumes (row sums / rho_s).
  const Real rho = solid.material.density;
  Real mass = 0;
  Vec3 moment = Vec3::Zero();
  body.nodal_volume = VectorX::Zero(solid.mesh.node_count());
  for (Index e = 0; e < solid.mesh.cell_count(); ++e) {
    const Index* cell = solid.mesh.cell(e);
    for (int a = 0; a < nodes; ++a)
      for (int c = 0; c < nodes; ++c) {
        const Real m = solid.cell_mass[static_cast<size_t>(e) * nodes * nodes + a * nodes + c];
        mass += m;
        moment += m * solid.mesh.nodes[cell[c]];
        body.nodal_volume[cell[a]] += m / rho;
      }
  }
  body.centre = moment / mass;
  // M = sum_CD M~_CD Q_C^T Q_D for a density: block (a, b) = sum M~_CD s_a(C) s_b(D) I with the
  // mesh's consistent mass M~ scaled by density / rho_s. The body's excess mass is the frame's mass
  // for rho_s - rho_f, the fluid it holds inside for rho_f.
  auto frame_mass = [&](Real density) {
    const Real scale = density / rho;
    MatrixXd blocks = MatrixXd::Zero(dim + 1, dim + 1);
    for (Index e = 0; e < solid.mesh.cell_count(); ++e) {
      const Index* cell = solid.mesh.cell(e);
      for (int a = 0; a < nodes; ++a)
        for (int c = 0; c < nodes; ++c) {
          const Real m = scale * solid.cell_mass[static_cast<size_t>(e) * nodes * nodes + a * nodes + c];
          const auto sa = rigid_node_weights(solid.mesh.nodes[cell[a]] - body.centre, dim);
          const auto sc = rigid_node_weights(solid.mesh.nodes[cell[c]] - body.centre, dim);
          for (int i = 0; i <= dim; ++i)
            for (int j = 0; j <= dim; ++j) blocks(i, j) += m * sa[i] * sc[j];
        }
    }
    MatrixXd M = MatrixXd::Zero(rigid_frame_size(dim), rigid_frame_size(dim));
    for (int i = 0; i <= dim; ++i)
      for (int j = 0; j <= dim; ++j)
        for (int k = 0; k < dim; ++k) M(i * dim + k, j * dim + k) = blocks(i, j);
    return M;
  };
  body.excess_mass = frame_mass(rho - fluid_density);
  body.fluid_mass = frame_mass(fluid_density);
  return body;
}

Real default_rigid_coupling_stiffness(const NavierStokesModel& fluid, Real dt) {
  const Real h = *std::min_element(fluid.cell_size.begin(), fluid.cell_size.end());
  return 1000 * (fluid.density / dt + fluid.viscosity / (h * h));
}

Vec3 rigid_frame_angular_velocity(const VectorX& frame, const VectorX& frame_velocity, int dim) {
  Vec3 w = Vec3::Zero();
  for (int i = 0; i < dim; ++i) w += 0.5 * frame_director(frame, i, dim).cross(frame_director(frame_velocity, i, dim));
  return w;
}

// The body's nodes at q_theta in the fluid: where each lies, the fluid's velocity gradient there
// and the coupling force lambda_C = k W_C (I(v_theta)(x_C) - Q_C dq_theta). False (with the
// reason in `failure`) if a node has left the fluid's mesh.
bool ImmersedRigidCoupling::evaluate_nodes(size_t b, const VectorX& x, const VectorX& x_n, Real theta, const VectorX& q_theta,
                                           BodyStep& s, std::string& failure) const {
  const ImmersedRigidBody& body = solids_.rigid_bodies[b];
  const FemSolid& solid = solids_.model.solids[body.solid];
  const int dim = solids_.model.dim;
  for (Index c = 0; c < solid.mesh.node_count(); ++c) {
    const auto w = rigid_node_weights(solid.mesh.nodes[c] - body.centre, dim);
    const Vec3 point = apply_rigid_node_map(w, q_theta, dim);
    const std::optional<MeshPoint> at = locator_.locate(point, s.at[c].cell);
    if (!at) {
      failure = fmt::format("rigid body '{}': node {} at ({:.6g}, {:.6g}, {:.6g}) m left the fluid's mesh", solid.name, c,
                            point.x(), point.y(), point.z());
      return false;
    }
    s.at[c] = *at;
    const Index* cell = fluid_.mesh.cell(at->cell);
    Vec3 fluid_velocity = Vec3::Zero();
    Mat3 G = Mat3::Zero();
    for (int a = 0; a < fluid_.mesh.nodes_per_cell(); ++a)
      for (int i = 0; i < dim; ++i) {
        const Index d = fluid_.dof(cell[a], i);
        const Real v = theta * x[d] + (1 - theta) * x_n[d];
        fluid_velocity[i] += at->shape[a] * v;
        G.row(i) += v * at->gradient[a].transpose();
      }
    s.gradient[c] = G;
    s.force[c] = body.coupling_stiffness * body.nodal_volume[c] * (fluid_velocity - apply_rigid_node_map(w, s.velocity_theta, dim));
  }
  return true;
}

// Newton's method on the body's equations F(dq_n+1, mu) = 0 at fixed fluid velocities (see the
// header), started from the frame's velocity at t_n. With y = dq_n+1, dq_theta = theta y +
// (1 - theta) dq_n, q_theta = q_n + theta dt dq_theta, x_C = Q_C q_theta and G_C = grad v_theta(x_C):
//   d lambda_C / dy = k W_C theta (theta dt G_C - I) Q_C,
//   dF_body/dy = M_e/dt + theta^2 dt mu . Hess g - sum_C Q_C^T d lambda_C/dy,   dF_body/d mu = G(q_theta)^T,
//   d g(q_n+1)/dy = theta dt G(q_n+1).
// A driven body's frame is its prescribed motion's (prescribed_rigid_motion.hpp), whatever the
// fluid does: dq_theta = (q_n+1 - q_n) / dt, dq_n+1 the motion's at t_n+1.
std::optional<ImmersedRigidCoupling::BodyStep> ImmersedRigidCoupling::solve_frame(size_t b, const VectorX& x,
                                                                                  const FlowTimeStep& step, Real theta,
                                                                                  const ImmersedSolidState& state,
                                                                                  std::string& failure) const {
  const ImmersedRigidBody& body = solids_.rigid_bodies[b];
  const FemSolid& solid = solids_.model.solids[body.solid];
  const int dim = solids_.model.dim, nq = rigid_frame_size(dim), ng = rigid_constraint_count(dim);
  const Index nodes = solid.mesh.node_count();
  const Real dt = step.dt;
  const VectorX& q0 = state.frame[b];
  const VectorX& dq0 = state.frame_velocity[b];
  const VectorX& x_n = *step.previous;
  BodyStep s;
  s.at.assign(nodes, MeshPoint{});
  s.force.assign(nodes, Vec3::Zero());
  s.gradient.assign(nodes, Mat3::Zero());
  if (body.motion) {
    s.next = advance_prescribed_frame(*body.motion, q0, state.time, dt, dim);
    s.velocity = prescribed_frame_velocity(*body.motion, s.next, state.time + dt, dim);
    s.velocity_theta = (s.next - q0) / dt;
    if (!evaluate_nodes(b, x, x_n, theta, q0 + theta * (s.next - q0), s, failure)) return std::nullopt;
    return s;
  }
  // Velocity scale for the convergence test: the fastest fluid velocity or frame velocity (its
  // directors' rates are per unit length, so this is a scale, not a node's speed).
  Real speed = dq0.lpNorm<Eigen::Infinity>();
  for (Index n = 0; n < fluid_.mesh.node_count(); ++n)
    for (int i = 0; i < dim; ++i) speed = std::max(speed, std::abs(x[fluid_.dof(n, i)]));
  // Converged when the correction is at round-off: below 1e-15 of the scale, or no longer
  // shrinking once below 1e-10 of it (the located points' round-off sets the floor).
  const Real scale = std::max(speed, smallest_cell_ / dt), tolerance = 1e-15 * scale, floor = 1e-10 * scale;

  s.velocity = dq0;
  VectorX mu = VectorX::Zero(ng);
  const Vec3 gravity = fluid_.body_force;
  Real last_change = kInfinity, change_before = kInfinity;
  for (int iteration = 0; iteration < 30; ++iteration) {
    s.velocity_theta = theta * s.velocity + (1 - theta) * dq0;
    s.next = q0 + dt * s.velocity_theta;
    const VectorX q_theta = q0 + theta * dt * s.velocity_theta;
    if (!evaluate_nodes(b, x, x_n, theta, q_theta, s, failure)) return std::nullopt;
    VectorX F = VectorX::Zero(nq + ng);
    MatrixXd& A = s.jacobian;
    A = MatrixXd::Zero(nq + ng, nq + ng);
    for (Index c = 0; c < nodes; ++c) {
      const auto w = rigid_node_weights(solid.mesh.nodes[c] - body.centre, dim);
      // F_body -= Q_C^T lambda;  A_body += k W theta Q_C^T (I - theta dt G) Q_C.
      const Mat3 S = body.coupling_stiffness * body.nodal_volume[c] * theta * (Mat3::Identity() - theta * dt * s.gradient[c]);
      for (int p = 0; p <= dim; ++p) {
        for (int i = 0; i < dim; ++i) F[p * dim + i] -= w[p] * s.force[c][i];
        for (int r = 0; r <= dim; ++r)
          for (int i = 0; i < dim; ++i)
            for (int j = 0; j < dim; ++j) A(p * dim + i, r * dim + j) += w[p] * w[r] * S(i, j);
      }
    }
    VectorX excess_gravity = VectorX::Zero(nq);
    for (int i = 0; i < dim; ++i) excess_gravity[i] = gravity[i];
    const MatrixXd G_theta = frame_constraint_jacobian(q_theta, dim);
    F.head(nq) += body.excess_mass * ((s.velocity - dq0) / dt - excess_gravity) + G_theta.transpose() * mu;
    F.tail(ng) = frame_constraints(s.next, dim);
    A.topLeftCorner(nq, nq) += body.excess_mass / dt;
    MatrixXd hessian = MatrixXd::Zero(nq, nq);
    add_frame_constraint_hessian(mu, theta * theta * dt, dim, hessian);
    A.topLeftCorner(nq, nq) += hessian;
    A.topRightCorner(nq, ng) = G_theta.transpose();
    A.bottomLeftCorner(ng, nq) = theta * dt * frame_constraint_jacobian(s.next, dim);
    if (last_change <= tolerance || (last_change <= floor && last_change > 0.25 * change_before)) return s;
    const VectorX correction = A.partialPivLu().solve(-F);
    if (!correction.allFinite()) break;
    s.velocity += correction.head(nq);
    mu += correction.tail(ng);
    // The correction's size: the largest change of a node's velocity (m/s, whatever the body's size).
    change_before = last_change;
    last_change = 0;
    for (Index c = 0; c < nodes; ++c) {
      const Vec3 change = apply_rigid_node_map(rigid_node_weights(solid.mesh.nodes[c] - body.centre, dim), correction.head(nq), dim);
      last_change = std::max(last_change, change.cwiseAbs().maxCoeff());
    }
  }
  failure = fmt::format("rigid body '{}': its frame's Newton iterations did not converge", solid.name);
  return std::nullopt;
}

std::string ImmersedRigidCoupling::add(const VectorX& x, const FlowTimeStep& step, Real theta,
                                       const ImmersedSolidState& state, VectorX& R,
                                       std::vector<Eigen::Triplet<Real, int>>* jacobian, FlowLowRank* low_rank) const {
  const int dim = solids_.model.dim, nq = rigid_frame_size(dim), ng = rigid_constraint_count(dim);
  const int cell_nodes = fluid_.mesh.nodes_per_cell();
  const Real dt = step.dt;
  for (size_t b = 0; b < solids_.rigid_bodies.size(); ++b) {
    std::string failure;
    const std::optional<BodyStep> s = solve_frame(b, x, step, theta, state, failure);
    if (!s) return failure;
    const ImmersedRigidBody& body = solids_.rigid_bodies[b];
    const FemSolid& solid = solids_.model.solids[body.solid];
    const Index nodes = solid.mesh.node_count();
    // R_A += sum_C N_A(x_C) lambda_C.
    for (Index c = 0; c < nodes; ++c) {
      const Index* cell = fluid_.mesh.cell(s->at[c].cell);
      for (int a = 0; a < cell_nodes; ++a)
        for (int i = 0; i < dim; ++i) R[fluid_.dof(cell[a], i)] += s->at[c].shape[a] * s->force[c][i];
    }
    if (!jacobian) continue;
    // The fluid's free velocity dofs the body touches, numbered locally in increasing order.
    std::vector<Index> local;
    for (Index c = 0; c < nodes; ++c) {
      const Index* cell = fluid_.mesh.cell(s->at[c].cell);
      for (int a = 0; a < cell_nodes; ++a)
        for (int i = 0; i < dim; ++i)
          if (fluid_.free_index[fluid_.dof(cell[a], i)] >= 0) local.push_back(fluid_.free_index[fluid_.dof(cell[a], i)]);
    }
    std::sort(local.begin(), local.end());
    local.erase(std::unique(local.begin(), local.end()), local.end());
    const Index n = static_cast<Index>(local.size());
    auto local_index = [&](Index free) {
      return static_cast<Index>(std::lower_bound(local.begin(), local.end(), free) - local.begin());
    };
    // The direct term theta M^T K M goes straight into the triplets; coupling = dF_body/dv (the
    // body rows) and response = dR/d(dq_n+1) are dense in the body's few frame dofs (a free body's
    // only: a driven body's frame does not depend on the fluid).
    const bool free = !body.motion;
    MatrixXd coupling = MatrixXd::Zero(nq + ng, n), response = MatrixXd::Zero(n, nq);
    for (Index c = 0; c < nodes; ++c) {
      const MeshPoint& at = s->at[c];
      const Index* cell = fluid_.mesh.cell(at.cell);
      const auto w = rigid_node_weights(solid.mesh.nodes[c] - body.centre, dim);
      const Real kW = body.coupling_stiffness * body.nodal_volume[c];
      // d lambda_C / d dq_n+1 = k W theta (theta dt G - I) Q_C, as a dim x nq block.
      MatrixXd slip_change = MatrixXd::Zero(dim, nq);
      const Mat3 S = kW * theta * (theta * dt * s->gradient[c] - Mat3::Identity());
      for (int r = 0; r <= dim; ++r)
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j) slip_change(i, r * dim + j) = w[r] * S(i, j);
      for (int a = 0; a < cell_nodes; ++a)
        for (int i = 0; i < dim; ++i) {
          const Index row = fluid_.free_index[fluid_.dof(cell[a], i)];
          if (row < 0) continue;
          const Index ra = local_index(row);
          for (int a2 = 0; a2 < cell_nodes; ++a2) {
            const Index column = fluid_.free_index[fluid_.dof(cell[a2], i)];
            const Real entry = theta * kW * at.shape[a] * at.shape[a2];
            if (column >= 0 && entry != 0) jacobian->emplace_back(static_cast<int>(row), static_cast<int>(column), entry);
          }
          // The spread force's change: N_A d lambda_C + lambda_C grad N_A . dx_C, dx_C = theta^2 dt Q_C d(dq).
          if (free)
            for (int r = 0; r <= dim; ++r)
            for (int j = 0; j < dim; ++j)
                response(ra, r * dim + j) += at.shape[a] * slip_change(i, r * dim + j) +
                                             s->force[c][i] * at.gradient[a][j] * theta * theta * dt * w[r];
        }
      if (!free) continue;
      // The body rows' dependence on the fluid: -Q_C^T k W theta M_C.
      for (int a = 0; a < cell_nodes; ++a)
        for (int i = 0; i < dim; ++i) {
          const Index column = fluid_.free_index[fluid_.dof(cell[a], i)];
          if (column < 0) continue;
          const Index ca = local_index(column);
          for (int p = 0; p <= dim; ++p) coupling(p * dim + i, ca) -= w[p] * kW * theta * at.shape[a];
        }
    }
    if (!free) continue;
    // d(dq_n+1)/dv = -[A^-1 coupling] (its frame rows); J = direct + response d(dq_n+1)/dv.
    const MatrixXd frame_change = -s->jacobian.partialPivLu().solve(coupling).topRows(nq);
    if (!low_rank) {
      const MatrixXd J = response * frame_change;
      for (Index j = 0; j < n; ++j)
        for (Index i = 0; i < n; ++i)
          if (J(i, j) != 0) jacobian->emplace_back(static_cast<int>(local[i]), static_cast<int>(local[j]), J(i, j));
    } else {
      // U = response, V^T = frame_change, scattered to the free dofs.
      const Eigen::Index first = low_rank->U.cols();
      if (first == 0) {
        low_rank->U.resize(fluid_.free_count, 0);
        low_rank->V.resize(fluid_.free_count, 0);
      }
      low_rank->U.conservativeResize(fluid_.free_count, first + nq);
      low_rank->V.conservativeResize(fluid_.free_count, first + nq);
      low_rank->U.rightCols(nq).setZero();
      low_rank->V.rightCols(nq).setZero();
      for (Index i = 0; i < n; ++i) {
        low_rank->U.row(local[i]).segment(first, nq) = response.row(i);
        low_rank->V.row(local[i]).segment(first, nq) = frame_change.col(i).transpose();
      }
    }
  }
  return {};
}

void ImmersedRigidCoupling::accept(const VectorX& x, const FlowTimeStep& step, Real theta, ImmersedSolidState& state) const {
  const int dim = solids_.model.dim;
  for (size_t b = 0; b < solids_.rigid_bodies.size(); ++b) {
    std::string failure;
    const std::optional<BodyStep> s = solve_frame(b, x, step, theta, state, failure);
    if (!s) throw NumericalError(failure);
    const ImmersedRigidBody& body = solids_.rigid_bodies[b];
    const FemSolid& solid = solids_.model.solids[body.solid];
    for (Index c = 0; c < solid.mesh.node_count(); ++c) {
      const auto w = rigid_node_weights(solid.mesh.nodes[c] - body.centre, dim);
      const Vec3 position = apply_rigid_node_map(w, s->next, dim), velocity = apply_rigid_node_map(w, s->velocity, dim);
      for (int i = 0; i < dim; ++i) {
        const Index d = solids_.model.dof(solid.node_begin + c, i);
        state.displacement[d] = position[i] - solid.mesh.nodes[c][i];
        state.velocity[d] = velocity[i];
      }
    }
    const auto [force, torque] = fluid_load(b, *s, step.dt, theta, state);
    state.fluid_force[body.solid] = force;
    state.fluid_torque[body.solid] = torque;
    state.frame[b] = s->next;
    state.frame_velocity[b] = s->velocity;
  }
}

// The fluid's force on a body over a step, from the balance of the fluid the body holds inside it:
// that fluid (density rho_f, moving with the body) feels the surrounding fluid's traction on the
// body's surface, its weight and the coupling's -lambda, so the traction's resultant, in the
// frame's generalized forces, is
//   f = sum_C Q_C^T lambda_C + M_f ((dq_n+1 - dq_n) / dt - (b, 0, ..)),
// with M_f the frame's mass at the fluid's density. Its phi block is the force (drag, lift and
// buoyancy); the torque about the centre is sum_i d_i x f_di (d_i at q_theta, where the body's
// points were), since sum_C (x_C - phi) x lambda_C = sum_i d_i x sum_C xi_Ci lambda_C. For a free
// body the balance gives f = M_s (acceleration - gravity) + G^T mu: Newton's law for the body.
std::pair<Vec3, Vec3> ImmersedRigidCoupling::fluid_load(size_t b, const BodyStep& s, Real dt, Real theta,
                                                        const ImmersedSolidState& state) const {
  const ImmersedRigidBody& body = solids_.rigid_bodies[b];
  const FemSolid& solid = solids_.model.solids[body.solid];
  const int dim = solids_.model.dim, nq = rigid_frame_size(dim);
  VectorX f = VectorX::Zero(nq);
  for (Index c = 0; c < solid.mesh.node_count(); ++c) {
    const auto w = rigid_node_weights(solid.mesh.nodes[c] - body.centre, dim);
    for (int p = 0; p <= dim; ++p)
      for (int i = 0; i < dim; ++i) f[p * dim + i] += w[p] * s.force[c][i];
  }
  VectorX acceleration = (s.velocity - state.frame_velocity[b]) / dt;
  for (int i = 0; i < dim; ++i) acceleration[i] -= fluid_.body_force[i];
  f += body.fluid_mass * acceleration;
  const VectorX q_theta = state.frame[b] + theta * dt * s.velocity_theta;
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  for (int k = 0; k < dim; ++k) force[k] = f[k];
  for (int i = 0; i < dim; ++i) torque += frame_director(q_theta, i, dim).cross(frame_director(f, i, dim));
  return {force, torque};
}

ImmersedSolidState initial_immersed_state(const ImmersedSolids& solids) {
  const Index dofs = solids.model.dof_count();
  const int dim = solids.model.dim;
  ImmersedSolidState state{VectorX::Zero(dofs), VectorX::Zero(dofs), 0, {}, {}, {}, {}, {}};
  for (const ImmersedRigidBody& body : solids.rigid_bodies) {
    state.frame.push_back(rigid_frame_at_rest(body, dim));
    state.frame_velocity.push_back(body.motion ? prescribed_frame_velocity(*body.motion, state.frame.back(), 0, dim)
                                               : VectorX::Zero(rigid_frame_size(dim)));
  }
  state.fluid_force.assign(solids.model.solids.size(), Vec3::Zero());
  state.fluid_torque.assign(solids.model.solids.size(), Vec3::Zero());
  return state;
}

}  // namespace moreau
