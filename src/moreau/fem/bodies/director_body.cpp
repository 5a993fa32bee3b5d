#include "moreau/fem/bodies/director_body.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace moreau {

namespace {

using Vec12 = DirectorVector;

// The director pairs of the six constraints: (i, i) for |d_i|^2/2 and (i, j) for d_i . d_j.
constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

Vec12 pack(const Vec3& phi, const std::array<Vec3, 3>& d) {
  Vec12 q;
  q << phi, d[0], d[1], d[2];
  return q;
}

Vec3 director(const Vec12& q, int i) { return q.segment<3>(3 + 3 * i); }

}  // namespace

DirectorVector director_configuration(const DirectorState& s) { return pack(s.phi, s.d); }
DirectorVector director_velocities(const DirectorState& s) { return pack(s.v_phi, s.v_d); }

DirectorVector director_mass(const DirectorBody& b) {
  Vec12 m;
  m << Vec3::Constant(b.mass), Vec3::Constant(b.euler[0]), Vec3::Constant(b.euler[1]), Vec3::Constant(b.euler[2]);
  return m;
}

Eigen::Matrix<Real, 6, 1> director_constraints(const DirectorVector& q) {
  Eigen::Matrix<Real, 6, 1> g;
  for (int k = 0; k < 6; ++k) {
    const int i = kPairs[k][0], j = kPairs[k][1];
    g[k] = i == j ? 0.5 * (director(q, i).squaredNorm() - 1) : director(q, i).dot(director(q, j));
  }
  return g;
}

Eigen::Matrix<Real, 6, 12> director_constraint_jacobian(const DirectorVector& q) {
  Eigen::Matrix<Real, 6, 12> G = Eigen::Matrix<Real, 6, 12>::Zero();
  for (int k = 0; k < 6; ++k) {
    const int i = kPairs[k][0], j = kPairs[k][1];
    if (i == j) {
      G.block<1, 3>(k, 3 + 3 * i) = director(q, i).transpose();
    } else {
      G.block<1, 3>(k, 3 + 3 * i) = director(q, j).transpose();
      G.block<1, 3>(k, 3 + 3 * j) = director(q, i).transpose();
    }
  }
  return G;
}

void add_director_constraint_hessian(const Eigen::Matrix<Real, 6, 1>& lambda, Real scale, Eigen::Ref<Eigen::Matrix<Real, 12, 12>> A) {
  for (int k = 0; k < 6; ++k) {
    const int i = kPairs[k][0], j = kPairs[k][1];
    const Real c = scale * lambda[k];
    A.block<3, 3>(3 + 3 * i, 3 + 3 * j).diagonal().array() += c;
    if (i != j) A.block<3, 3>(3 + 3 * j, 3 + 3 * i).diagonal().array() += c;
  }
}

// Generalised external force at the midpoint: the force on phi and director forces
// f_i = t x d_i / 2 with the moment sum_i d_i x f_i = S t, S = (1/2) sum_i (|d_i|^2 I - d_i d_i^T).
// The midpoint directors are not orthonormal (S = I only up to O((w h)^2)), so t = S^-1 tau makes
// the moment exactly tau: the angular momentum then grows by exactly h tau per step.
DirectorVector director_external_force(const DirectorVector& q_mid, const Vec3& force, const Vec3& torque) {
  Mat3 S = Mat3::Zero();
  for (int i = 0; i < 3; ++i)
    S += 0.5 * (director(q_mid, i).squaredNorm() * Mat3::Identity() - director(q_mid, i) * director(q_mid, i).transpose());
  const Vec3 t = torque.isZero(0) ? Vec3::Zero() : Vec3(S.partialPivLu().solve(torque));
  Vec12 f;
  f << force, 0.5 * t.cross(director(q_mid, 0)), 0.5 * t.cross(director(q_mid, 1)), 0.5 * t.cross(director(q_mid, 2));
  return f;
}

void set_director_step(const DirectorVector& q0, const DirectorVector& v0, const DirectorVector& q1, Real h,
                       DirectorState& s) {
  const Vec12 v1 = (2 / h) * (q1 - q0) - v0;
  s.phi = q1.head<3>();
  s.v_phi = v1.head<3>();
  for (int i = 0; i < 3; ++i) {
    s.d[i] = director(q1, i);
    s.v_d[i] = v1.segment<3>(3 + 3 * i);
  }
}

namespace {

// Rodrigues: exp(theta^) = I + sin|t|/|t| t^ + (1 - cos|t|)/|t|^2 t^ t^.
Mat3 rotation(const Vec3& theta) {
  const Real angle = theta.norm();
  if (angle < 1e-300) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

}  // namespace

DirectorBody director_body_from_inertia(Real mass, const Vec3& J, const Vec3& centre, const Mat3& axes) {
  DirectorBody b;
  b.mass = mass;
  b.centre = centre;
  b.axes = axes;
  for (int i = 0; i < 3; ++i) b.euler[i] = 0.5 * (J[(i + 1) % 3] + J[(i + 2) % 3] - J[i]);
  return b;
}

DirectorBody director_body_from_mesh(const FemMesh& mesh, Real density) {
  const auto rule = gauss_rule(mesh.element, 2);
  Real N[kMaxElementNodes];
  Vec3 dN[kMaxElementNodes];
  Real mass = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (Index e = 0; e < mesh.cell_count(); ++e)
    for (const QuadraturePoint& q : rule) {
      shape_functions(mesh.element, q.xi, N, dN);
      const Real w = density * q.weight * cell_jacobian(mesh, e, dN).determinant();
      Vec3 X = Vec3::Zero();
      for (int a = 0; a < mesh.nodes_per_cell(); ++a) X += N[a] * mesh.nodes[mesh.cell(e)[a]];
      mass += w;
      first += w * X;
      second += w * X * X.transpose();
    }
  DirectorBody b;
  b.mass = mass;
  b.centre = first / mass;
  const Mat3 euler = second - mass * b.centre * b.centre.transpose();  // about the centre of mass
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(euler);
  b.euler = eigen.eigenvalues();
  b.axes = eigen.eigenvectors();
  if (b.axes.determinant() < 0) b.axes.col(2) *= -1;
  return b;
}

DirectorState director_state_at_rest_pose(const DirectorBody& body, const Vec3& velocity, const Vec3& w) {
  DirectorState s;
  s.phi = body.centre;
  s.v_phi = velocity;
  for (int i = 0; i < 3; ++i) {
    s.d[i] = body.axes.col(i);
    s.v_d[i] = w.cross(s.d[i]);
  }
  return s;
}

DirectorStepRows director_step_rows(const DirectorBody& body, const DirectorVector& q0, const DirectorVector& v0, Real h,
                                    const Vec3& force, const Vec3& torque, const DirectorVector& q1,
                                    const Eigen::Matrix<Real, 6, 1>& lambda, bool with_jacobian) {
  const Vec12 M = director_mass(body);
  const Vec12 qm = 0.5 * (q0 + q1);
  const Eigen::Matrix<Real, 6, 12> Gm = director_constraint_jacobian(qm);
  DirectorStepRows rows;
  const Vec12 inertia = M.asDiagonal() * ((2 / (h * h)) * (q1 - q0) - (2 / h) * v0);
  const Vec12 external = director_external_force(qm, force, torque);
  rows.residual.head<12>() = inertia + Gm.transpose() * lambda - external;
  rows.residual.tail<6>() = director_constraints(q1);
  rows.force_scale = std::max({inertia.norm(), external.norm(), Real(1e-300)});
  if (!with_jacobian) return rows;
  auto& A = rows.jacobian;
  A.setZero();
  A.topLeftCorner<12, 12>().diagonal() = (2 / (h * h)) * M;
  add_director_constraint_hessian(lambda, 0.5, A.topLeftCorner<12, 12>());
  for (int i = 0; i < 3; ++i) A.block<3, 3>(3 + 3 * i, 3 + 3 * i) -= 0.25 * cross_matrix(torque);
  A.topRightCorner<12, 6>() = Gm.transpose();
  A.bottomLeftCorner<6, 12>() = director_constraint_jacobian(q1);
  return rows;
}

NewtonResult step_director_body(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                                DirectorState& state, const NewtonSettings& settings) {
  NewtonResult result;
  const Vec12 q0 = pack(state.phi, state.d), v0 = director_velocities(state);
  Vec12 q1 = q0 + h * v0;
  Eigen::Matrix<Real, 6, 1> lambda = Eigen::Matrix<Real, 6, 1>::Zero();
  for (;;) {
    const DirectorStepRows rows = director_step_rows(body, q0, v0, h, force, torque, q1, lambda, true);
    const Real momentum_norm = rows.residual.head<12>().norm(), constraint_norm = rows.residual.tail<6>().norm();
    result.residual_norms.push_back(momentum_norm / rows.force_scale + constraint_norm);
    if (momentum_norm <= settings.tolerance * rows.force_scale && constraint_norm <= settings.tolerance) break;
    if (result.iterations == settings.max_iterations) {
      result.failure = "the director body's step did not converge";
      return result;
    }
    const Eigen::Matrix<Real, 18, 1> dx = rows.jacobian.partialPivLu().solve(-rows.residual);
    ++result.iterations;
    q1 += dx.head<12>();
    lambda += dx.tail<6>();
    // On the residual's round-off floor (it has stopped falling), a correction below tolerance
    // times the step's motion is convergence, as in the solids' steps.
    const auto& norms = result.residual_norms;
    const bool stagnating = norms.size() >= 2 && norms.back() > 0.5 * norms[norms.size() - 2];
    if (stagnating && dx.head<12>().norm() <= settings.tolerance * (q1 - q0).norm() && constraint_norm <= settings.tolerance)
      break;
  }
  result.converged = true;
  set_director_step(q0, v0, q1, h, state);
  return result;
}

NewtonResult step_director_body_reduced(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                                        DirectorState& state, const NewtonSettings& settings) {
  NewtonResult result;
  const Vec12 M = director_mass(body);
  const Vec12 q0 = pack(state.phi, state.d), v0 = director_velocities(state);
  // q1(u): phi + u_phi, exp(theta^) d_i; exact on the constraint manifold.
  auto configuration = [&](const Eigen::Matrix<Real, 6, 1>& u) {
    const Mat3 R = rotation(u.tail<3>());
    return pack(state.phi + u.head<3>(), {R * state.d[0], R * state.d[1], R * state.d[2]});
  };
  // P(q_m)^T times the momentum balance: the force balance and sum_i d_i,m x r_i.
  auto reduced_residual = [&](const Eigen::Matrix<Real, 6, 1>& u) {
    const Vec12 q1 = configuration(u), qm = 0.5 * (q0 + q1);
    const Vec12 r = M.asDiagonal() * ((2 / h) * (q1 - q0) - 2 * v0) - h * director_external_force(qm, force, torque);
    Eigen::Matrix<Real, 6, 1> out;
    out.head<3>() = r.head<3>();
    out.tail<3>() = Vec3::Zero();
    for (int i = 0; i < 3; ++i) out.tail<3>() += director(qm, i).cross(r.segment<3>(3 + 3 * i));
    return out;
  };
  // Predictor: the explicit step's translation and the rotation of w h.
  Eigen::Matrix<Real, 6, 1> u;
  u << h * state.v_phi, h * angular_velocity(state);
  const Real scale = std::max({(M.asDiagonal() * (2 * v0)).norm(), h * force.norm(), h * torque.norm(), Real(1e-300)});
  for (;;) {
    const Eigen::Matrix<Real, 6, 1> r = reduced_residual(u);
    result.residual_norms.push_back(r.norm() / scale);
    if (r.norm() <= settings.tolerance * scale) break;
    if (result.iterations == settings.max_iterations) {
      result.failure = "the director body's reduced step did not converge";
      return result;
    }
    // Jacobian by central differences (6 x 6, step 1e-7 of the increment's scale): accurate to
    // ~1e-9 relative, so Newton reaches the tolerance at the quadratic rate.
    Eigen::Matrix<Real, 6, 6> J;
    const Real step = 1e-7 * std::max(u.norm(), Real(1e-3));
    for (int c = 0; c < 6; ++c) {
      Eigen::Matrix<Real, 6, 1> up = u, um = u;
      up[c] += step;
      um[c] -= step;
      J.col(c) = (reduced_residual(up) - reduced_residual(um)) / (2 * step);
    }
    const Eigen::Matrix<Real, 6, 1> du = J.partialPivLu().solve(-r);
    ++result.iterations;
    u += du;
    if (du.norm() <= 1e-3 * settings.tolerance * u.norm()) break;
  }
  result.converged = true;
  set_director_step(q0, v0, configuration(u), h, state);
  return result;
}

Real kinetic_energy(const DirectorBody& body, const DirectorState& s) {
  Real T = 0.5 * body.mass * s.v_phi.squaredNorm();
  for (int i = 0; i < 3; ++i) T += 0.5 * body.euler[i] * s.v_d[i].squaredNorm();
  return T;
}

Vec3 angular_momentum(const DirectorBody& body, const DirectorState& s) {
  Vec3 L = body.mass * s.phi.cross(s.v_phi);
  for (int i = 0; i < 3; ++i) L += body.euler[i] * s.d[i].cross(s.v_d[i]);
  return L;
}

Vec3 angular_velocity(const DirectorState& s) {
  Vec3 w = Vec3::Zero();
  for (int i = 0; i < 3; ++i) w += 0.5 * s.d[i].cross(s.v_d[i]);
  return w;
}

Real director_constraint_error(const DirectorState& s) { return director_constraints(pack(s.phi, s.d)).cwiseAbs().maxCoeff(); }

}  // namespace moreau
