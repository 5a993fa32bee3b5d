#include "moreau/fem/bodies/director_body.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {

using Vec6 = Eigen::Matrix<Real, 6, 1>;
using Vec18 = Eigen::Matrix<Real, 18, 1>;

// The multiplier form of a body's step: unknowns q1 (12) and the internal multipliers (6).
struct DirectorStepIterate {
  Vec12 q1;                         // the configuration at the step's end
  Vec6 lambda;                      // the internal multipliers
  DirectorStepRows rows;            // residual and Jacobian there
  Real constraint_norm = 0;         // |g(q1)|
};

class DirectorStepSystem final : public NewtonIterates<DirectorStepIterate> {
 public:
  DirectorStepSystem(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque, const DirectorState& state,
                     const NewtonSettings& settings)
      : body_(body), h_(h), force_(force), torque_(torque), settings_(settings), q0_(pack(state.phi, state.d)),
        v0_(director_velocities(state)) {
    now_.q1 = q0_ + h * v0_;
    now_.lambda = Vec6::Zero();
  }

  NewtonEvaluation evaluate(const VectorX* dx, Real alpha) override {
    trial_.q1 = now_.q1;
    trial_.lambda = now_.lambda;
    if (dx) {
      trial_.q1 += alpha * dx->head<12>();
      trial_.lambda += alpha * dx->tail<6>();
    }
    trial_.rows = director_step_rows(body_, q0_, v0_, h_, force_, torque_, trial_.q1, trial_.lambda, true);
    const DirectorStepRows& rows = trial_.rows;
    const Real momentum_norm = rows.residual.head<12>().norm(), constraint_norm = rows.residual.tail<6>().norm();
    NewtonEvaluation e;
    e.norm = momentum_norm / rows.force_scale + constraint_norm;
    e.converged = momentum_norm <= settings_.tolerance * rows.force_scale && constraint_norm <= settings_.tolerance;
    e.relative = std::max(momentum_norm / rows.force_scale, constraint_norm);
    e.describe = fmt::format("force residual {:.3e} of {:.3e}, constraint residual {:.3e}", momentum_norm,
                             rows.force_scale, constraint_norm);
    trial_.constraint_norm = constraint_norm;
    if (!dx) accept();
    return e;
  }
  bool solve(VectorX& dx, std::string&) override {
    dx = now_.rows.jacobian.partialPivLu().solve(-now_.rows.residual);
    return true;
  }
  // The correction of q1 against the step's motion; none counts while the constraints are violated.
  Real relative_correction(const VectorX& dx, Real alpha) const override {
    if (now_.constraint_norm > settings_.tolerance) return std::numeric_limits<Real>::infinity();
    return alpha * dx.head<12>().norm() / std::max((now_.q1 - q0_).norm(), Real(1e-300));
  }

  void finish(DirectorState& state) const { set_director_step(q0_, v0_, now_.q1, h_, state); }

 private:
  const DirectorBody& body_;
  Real h_;
  Vec3 force_, torque_;
  const NewtonSettings& settings_;
  Vec12 q0_, v0_;
};

// The null-space form: six unknowns u (translation, rotation vector) with q1(u) = (phi + u_phi,
// exp(theta^) d_i), exact on the constraint manifold, and the residual P(q_m)^T times the momentum
// balance: the force balance and sum_i d_i,m x r_i.
struct ReducedDirectorIterate {
  Vec6 u;  // translation and rotation vector of the step
  Vec6 r;  // the reduced residual there
};

class ReducedDirectorStepSystem final : public NewtonIterates<ReducedDirectorIterate> {
 public:
  ReducedDirectorStepSystem(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                            const DirectorState& state, const NewtonSettings& settings)
      : h_(h), force_(force), torque_(torque), settings_(settings), state_(state), M_(director_mass(body)),
        q0_(pack(state.phi, state.d)), v0_(director_velocities(state)) {
    // Predictor: the explicit step's translation and the rotation of w h.
    now_.u << h * state.v_phi, h * angular_velocity(state);
    scale_ = std::max({(M_.asDiagonal() * (2 * v0_)).norm(), h * force.norm(), h * torque.norm(), Real(1e-300)});
  }

  Vec12 configuration(const Vec6& u) const {
    const Mat3 R = rotation(u.tail<3>());
    return pack(state_.phi + u.head<3>(), {R * state_.d[0], R * state_.d[1], R * state_.d[2]});
  }

  NewtonEvaluation evaluate(const VectorX* du, Real alpha) override {
    trial_.u = now_.u;
    if (du) trial_.u += alpha * du->head<6>();
    const Vec6 r = residual(trial_.u);
    NewtonEvaluation e;
    e.norm = r.norm() / scale_;
    e.converged = r.norm() <= settings_.tolerance * scale_;
    e.relative = e.norm;
    e.describe = fmt::format("|r| = {:.3e}, scale {:.3e}", r.norm(), scale_);
    trial_.r = r;
    if (!du) accept();
    return e;
  }
  // Jacobian by central differences (6 x 6, step 1e-7 of the increment's scale): accurate to
  // ~1e-9 relative, so Newton reaches the tolerance at the quadratic rate.
  bool solve(VectorX& du, std::string&) override {
    Eigen::Matrix<Real, 6, 6> J;
    const Real step = 1e-7 * std::max(now_.u.norm(), Real(1e-3));
    for (int c = 0; c < 6; ++c) {
      Vec6 up = now_.u, um = now_.u;
      up[c] += step;
      um[c] -= step;
      J.col(c) = (residual(up) - residual(um)) / (2 * step);
    }
    du = J.partialPivLu().solve(-now_.r);
    return true;
  }
  Real relative_correction(const VectorX& du, Real alpha) const override {
    return alpha * du.norm() / std::max(now_.u.norm(), Real(1e-300));
  }

  void finish(DirectorState& state) const { set_director_step(q0_, v0_, configuration(now_.u), h_, state); }

 private:
  Vec6 residual(const Vec6& u) const {
    const Vec12 q1 = configuration(u), qm = 0.5 * (q0_ + q1);
    const Vec12 r = M_.asDiagonal() * ((2 / h_) * (q1 - q0_) - 2 * v0_) - h_ * director_external_force(qm, force_, torque_);
    Vec6 out;
    out.head<3>() = r.head<3>();
    out.tail<3>() = Vec3::Zero();
    for (int i = 0; i < 3; ++i) out.tail<3>() += director(qm, i).cross(r.segment<3>(3 + 3 * i));
    return out;
  }

  Real h_;
  Vec3 force_, torque_;
  const NewtonSettings& settings_;
  const DirectorState& state_;
  Vec12 M_, q0_, v0_;
  Real scale_ = 1;
};

}  // namespace

namespace {

// Newton on one step of either form; the state is written only when it converges.
template <class System>
NewtonResult solve_director_step(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                                 DirectorState& state, const NewtonSettings& settings, const char* what) {
  NewtonResult result;
  System system(body, h, force, torque, state, settings);
  if (!newton_solve(system, settings, what, result)) return result;
  result.converged = true;
  system.finish(state);
  return result;
}

}  // namespace

NewtonResult step_director_body(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                                DirectorState& state, const NewtonSettings& settings) {
  return solve_director_step<DirectorStepSystem>(body, h, force, torque, state, settings, "the director body's step");
}

NewtonResult step_director_body_reduced(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                                        DirectorState& state, const NewtonSettings& settings) {
  return solve_director_step<ReducedDirectorStepSystem>(body, h, force, torque, state, settings,
                                                        "the director body's reduced step");
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
