#pragma once
// Rigid bodies of the FEM engine as constrained director frames (Betsch &
// Steinmann 2001, "Constrained integration of rigid body dynamics", CMAME 191). A body is
//   q = (phi, d1, d2, d3) in R^12   (centre of mass and three body-fixed unit directors)
// with the constant mass matrix M = diag(m I, E1 I, E2 I, E3 I), E_i = integral of rho X_i^2 dV
// about the centre of mass along the principal axes (the Euler tensor; E_i = (J_j + J_k - J_i)/2
// from the principal moments J), and six internal constraints
//   g = (|d1|^2 - 1, |d2|^2 - 1, |d3|^2 - 1)/2, d1.d2, d1.d3, d2.d3.
// Kinetic energy T = v^T M v / 2 is quadratic, so the body is a constrained particle system.
//
// Midpoint scheme with the constraints at n+1 (the reference form, Lagrange multipliers):
//   q1 - q0 = h/2 (v0 + v1)
//   M (v1 - v0) = -h G(q_{1/2})^T lambda + h f_ext
//   g(q1) = 0
// g is quadratic, so G(q_{1/2}) (q1 - q0) = g(q1) - g(q0) = 0: the constraint forces do no work,
// and energy and angular momentum are conserved exactly (to the Newton tolerance) at any h.
// External torque tau enters as director forces f_i = t x d_i / 2 at the midpoint, with t chosen
// so that their moment sum d_i x f_i is exactly tau (t = tau for orthonormal directors).
#include <array>

#include "moreau/fem/core/fem_mesh.hpp"
#include "moreau/fem/solids/static_solver.hpp"

namespace moreau {

struct DirectorBody {
  Real mass = 0;                  // kg
  Vec3 euler = Vec3::Zero();      // E1, E2, E3, kg m^2
  Vec3 centre = Vec3::Zero();     // reference centre of mass, m
  Mat3 axes = Mat3::Identity();   // reference directors (principal axes) as columns
};

struct DirectorState {
  Vec3 phi = Vec3::Zero();                 // centre of mass, m
  std::array<Vec3, 3> d{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  Vec3 v_phi = Vec3::Zero();               // m/s
  std::array<Vec3, 3> v_d{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
};

/// Mass, centre and Euler tensor (principal axes sorted by increasing E_i, right-handed) of a
/// mesh of density rho, integrated with the cells' degree-2 Gauss rule.
DirectorBody director_body_from_mesh(const FemMesh& mesh, Real density);

/// A body from its mass and principal moments of inertia J (about axes `axes`, columns).
DirectorBody director_body_from_inertia(Real mass, const Vec3& principal_inertia, const Vec3& centre,
                                        const Mat3& axes = Mat3::Identity());

/// The state of a body at its reference pose moving with velocity v and angular velocity w
/// (world): d_i = axes_i, v_d_i = w x d_i.
DirectorState director_state_at_rest_pose(const DirectorBody& body, const Vec3& velocity, const Vec3& angular_velocity);

/// One midpoint step with the internal constraints at n+1, by Newton on (q1, lambda) (18 x 18).
/// `force` acts at the centre of mass, `torque` through director forces; both at t_{n+1/2}.
NewtonResult step_director_body(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                                DirectorState& state, const NewtonSettings& settings = {});

/// The same step by the discrete null-space method (Betsch & Leyendecker 2006): the directors
/// are rotated by the Rodrigues map of an increment theta, d_i1 = exp(theta^) d_i0, so g(q1) = 0
/// holds by construction; premultiplying the momentum balance by P(q_{1/2})^T, with
/// P = [I 0; 0 -d1^; 0 -d2^; 0 -d3^] (G P = 0), removes the multipliers, leaving six equations in
/// (u_phi, theta), solved by Newton.
NewtonResult step_director_body_reduced(const DirectorBody& body, Real h, const Vec3& force, const Vec3& torque,
                                        DirectorState& state, const NewtonSettings& settings = {});

// Building blocks shared with the coupled step (coupled_step.cpp): q and v packed as 12-vectors
// (phi, d1, d2, d3), the diagonal of M, the internal constraints g(q), their Jacobian G(q) and
// lambda . Hess g (constant: I on the director blocks of each pair), and the generalised force.
using DirectorVector = Eigen::Matrix<Real, 12, 1>;
DirectorVector director_configuration(const DirectorState& state);
DirectorVector director_velocities(const DirectorState& state);
DirectorVector director_mass(const DirectorBody& body);
Eigen::Matrix<Real, 6, 1> director_constraints(const DirectorVector& q);
Eigen::Matrix<Real, 6, 12> director_constraint_jacobian(const DirectorVector& q);
/// A += scale * sum_k lambda_k Hess(g_k).
void add_director_constraint_hessian(const Eigen::Matrix<Real, 6, 1>& lambda, Real scale,
                                     Eigen::Ref<Eigen::Matrix<Real, 12, 12>> A);
DirectorVector director_external_force(const DirectorVector& q_mid, const Vec3& force, const Vec3& torque);
/// One body's rows of the constrained midpoint step, in force units, at the trial q1 and internal
/// multipliers lambda (shared by step_director_body and the coupled step):
///   residual = [M (2/h^2 (q1 - q0) - 2/h v0) + G(q_m)^T lambda - f(q_m);  g(q1)],  q_m = (q0 + q1)/2
///   jacobian = [2/h^2 M + 1/2 lambda . Hess g - 1/4 [tau]x on each director,  G(q_m)^T;  G(q1),  0]
/// (the torque forces' dependence through S^-1 is left out of the Jacobian: second order), and
/// force_scale = max(|inertia term|, |f(q_m)|), the scale of the momentum rows (as for the solids).
struct DirectorStepRows {
  Eigen::Matrix<Real, 18, 1> residual;
  Eigen::Matrix<Real, 18, 18> jacobian;
  Real force_scale = 0;
};
DirectorStepRows director_step_rows(const DirectorBody& body, const DirectorVector& q0, const DirectorVector& v0, Real h,
                                    const Vec3& force, const Vec3& torque, const DirectorVector& q1,
                                    const Eigen::Matrix<Real, 6, 1>& lambda, bool with_jacobian);

/// The state after a step from (q0, v0) to q1: v1 = 2 (q1 - q0)/h - v0.
void set_director_step(const DirectorVector& q0, const DirectorVector& v0, const DirectorVector& q1, Real h,
                       DirectorState& state);

Real kinetic_energy(const DirectorBody& body, const DirectorState& state);
/// L = phi x m v_phi + sum_i d_i x E_i v_d_i (about the origin).
Vec3 angular_momentum(const DirectorBody& body, const DirectorState& state);
/// The angular velocity (world) from the directors: w = 1/2 sum_i d_i x v_d_i.
Vec3 angular_velocity(const DirectorState& state);
/// max |g_k(q)|: how far the directors are from orthonormal.
Real director_constraint_error(const DirectorState& state);

}  // namespace moreau
