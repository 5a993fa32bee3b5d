// Joints of the FEM engine, solved in one Newton system with bodies and solids: the coupled step
// reproduces the free body's step, a compound pendulum on a spherical joint keeps its energy and
// swings with the analytic period, a hinge keeps its axis, and a soft beam pinned to a free body
// keeps the system's energy and momenta.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem_test_helpers.hpp"
#include "moreau/fem/bodies/coupled_step.hpp"

namespace moreau {
namespace {

FemRigidBody box_body(const std::string& name, const Vec3& min, const Vec3& max, Real density) {
  FemRigidBody b;
  b.name = name;
  b.mesh = make_box_mesh(min, max, {2, 2, 2}, ElementType::hex8);
  b.body = director_body_from_mesh(b.mesh, density);
  b.initial = director_state_at_rest_pose(b.body, Vec3::Zero(), Vec3::Zero());
  return b;
}

FemJointEnd body_point(const FemRigidBody& b, Index index, const Vec3& point) {
  return {FemJointEndKind::body, index, b.body.axes.transpose() * (point - b.body.centre)};
}

FemRunState start(const FemProblem& p) {
  FemRunState run;
  run.solids = initial_dynamic_state(p.model);
  for (const FemRigidBody& b : p.rigid_bodies) run.bodies.push_back(b.initial);
  return run;
}

TEST(FemJoints, CoupledStepOfAFreeBodyIsTheBodysStep) {
  // No solids, no joints: the coupled system reduces to the body's own (its rows divided by h),
  // so 100 steps of a spinning, falling box agree with step_director_body to the tolerance.
  FemProblem p;
  p.model.dim = 3;
  finalize_fem_model(p.model);
  p.rigid_bodies.push_back(box_body("b", Vec3(-0.5, -0.25, -0.1), Vec3(0.5, 0.25, 0.1), 1000));
  p.rigid_bodies[0].initial = director_state_at_rest_pose(p.rigid_bodies[0].body, Vec3(1, 2, 0), Vec3(0.1, 5, 0.1));
  p.gravity = Vec3(0, -9.81, 0);
  FemRunState run = start(p);
  DirectorState alone = p.rigid_bodies[0].initial;
  SparseLuSolver solver;
  for (int k = 0; k < 100; ++k) {
    const NewtonResult r = step_coupled(p, SparseMatrix(), StepRule::energy_momentum, 0.01, run, solver, {.tolerance = 1e-13});
    ASSERT_TRUE(r.converged) << r.failure;
    ASSERT_TRUE(step_director_body(p.rigid_bodies[0].body, 0.01, p.rigid_bodies[0].body.mass * p.gravity, Vec3::Zero(), alone,
                                   {.tolerance = 1e-13})
                    .converged);
  }
  EXPECT_LT((run.bodies[0].phi - alone.phi).norm(), 1e-10);
  for (int i = 0; i < 3; ++i) EXPECT_LT((run.bodies[0].d[i] - alone.d[i]).norm(), 1e-10);
}

TEST(FemJoints, CompoundPendulumOnASphericalJoint) {
  // A 0.2 x 0.6 x 0.2 m box (24 kg) hanging from a spherical joint to the world at its top face's
  // centre, released from 10 degrees about z, 4 s at h = 0.005. Energy T - m g . phi is constant
  // (the joint force does no work over a step: its rows are linear in q) to 1e-9 relative, the
  // joint holds to 1e-10 m, and the period matches the compound pendulum's
  // 2 pi sqrt(I_pivot / (m g d)) (d = 0.3 m, I_pivot = m (0.2^2 + 0.6^2)/12 + m d^2) with the
  // large-amplitude factor 1 + theta0^2/16 to 0.2 % (the midpoint rule's phase error, O(h^2 w^2)).
  FemProblem p;
  p.model.dim = 3;
  finalize_fem_model(p.model);
  FemRigidBody b = box_body("bob", Vec3(-0.1, -0.6, -0.1), Vec3(0.1, 0, 0.1), 1000);
  const Real theta0 = 10 * kPi / 180;
  // Rotate the body about the pivot (the origin) by theta0 about z.
  const Mat3 R = Eigen::AngleAxisd(theta0, Vec3::UnitZ()).toRotationMatrix();
  b.initial.phi = R * b.body.centre;
  for (int i = 0; i < 3; ++i) b.initial.d[i] = R * b.body.axes.col(i);
  p.rigid_bodies.push_back(b);
  FemJoint j;
  j.name = "pivot";
  j.rows.push_back({FemJointRows::Kind::coincide, body_point(b, 0, Vec3::Zero()), {FemJointEndKind::world, -1, Vec3::Zero()}});
  p.joints.push_back(j);
  p.gravity = Vec3(0, -9.81, 0);
  FemRunState run = start(p);
  SparseLuSolver solver;
  const Real m = b.body.mass, h = 0.005;
  auto energy = [&] { return kinetic_energy(b.body, run.bodies[0]) - m * p.gravity.dot(run.bodies[0].phi); };
  const Real E0 = energy();
  Real drift = 0, violation = 0;
  std::vector<Real> crossings;  // upward zero crossings of the angle
  Real previous = theta0;
  for (int k = 0; k < 800; ++k) {
    const NewtonResult r = step_coupled(p, SparseMatrix(), StepRule::energy_momentum, h, run, solver, {.tolerance = 1e-12});
    ASSERT_TRUE(r.converged) << r.failure;
    drift = std::max(drift, std::abs(energy() - E0) / std::abs(E0));
    violation = std::max(violation, joint_violation(p, run, p.joints[0]));
    const Real angle = std::atan2(run.bodies[0].phi.x(), -run.bodies[0].phi.y());
    if (previous < 0 && angle >= 0) crossings.push_back((k + previous / (previous - angle)) * h);
    previous = angle;
  }
  ASSERT_GE(crossings.size(), 2u);
  const Real d = 0.3, I = m * (0.04 + 0.36) / 12 + m * d * d;
  const Real period = 2 * kPi * std::sqrt(I / (m * 9.81 * d)) * (1 + theta0 * theta0 / 16);
  const Real measured = crossings[1] - crossings[0];
  std::printf("compound pendulum: period %.5f s (analytic %.5f), energy drift %.2e, joint %.2e m\n", measured, period, drift,
              violation);
  EXPECT_NEAR(measured, period, 0.002 * period);
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(violation, 1e-10);
}

TEST(FemJoints, TwoBodiesOnAHingeKeepEnergyMomentaAndTheAxis) {
  // Two boxes joined by a hinge (axis z through their common face centre), thrown
  // tumbling with different spins, no gravity. The axis rows n_a . e_b = 0 are quadratic in the
  // directors, so their forces at the midpoint do no work either: energy and both momenta stay
  // constant to the tolerance, the anchor and the axis hold to 1e-10, and the relative rotation
  // is about the axis only. Newton converges in a few iterations (the axis rows' Hessian is in
  // the Jacobian).
  FemProblem p;
  p.model.dim = 3;
  finalize_fem_model(p.model);
  FemRigidBody a = box_body("a", Vec3(-0.4, -0.1, -0.1), Vec3(0, 0.1, 0.1), 1000);
  FemRigidBody b = box_body("b", Vec3(0, -0.1, -0.05), Vec3(0.3, 0.1, 0.05), 800);
  a.initial = director_state_at_rest_pose(a.body, Vec3(0.1, 0, 0), Vec3(0.5, 1.0, 2.0));
  // b's velocity field matches a's at the anchor (the origin), plus a spin about the axis.
  const Vec3 wb = Vec3(0.5, 1.0, 2.0) + Vec3(0, 0, 3);
  const Vec3 anchor_velocity = Vec3(0.1, 0, 0) + Vec3(0.5, 1.0, 2.0).cross(-a.body.centre);
  b.initial = director_state_at_rest_pose(b.body, anchor_velocity + wb.cross(b.body.centre), wb);
  p.rigid_bodies = {a, b};
  FemJoint j;
  j.name = "hinge";
  j.rows.push_back({FemJointRows::Kind::coincide, body_point(a, 0, Vec3::Zero()), body_point(b, 1, Vec3::Zero())});
  const Vec3 normals[2] = {Vec3::UnitX(), Vec3::UnitY()};
  for (const Vec3& e : normals) {
    FemJointRows row{FemJointRows::Kind::perpendicular, body_point(a, 0, Vec3::Zero()), body_point(b, 1, Vec3::Zero())};
    row.direction_a = a.body.axes.transpose() * Vec3::UnitZ();
    row.direction_b = b.body.axes.transpose() * e;
    j.rows.push_back(row);
  }
  p.joints.push_back(j);
  FemRunState run = start(p);
  SparseLuSolver solver;
  auto energy = [&] { return kinetic_energy(a.body, run.bodies[0]) + kinetic_energy(b.body, run.bodies[1]); };
  auto momentum = [&] { return Vec3(angular_momentum(a.body, run.bodies[0]) + angular_momentum(b.body, run.bodies[1])); };
  const Real E0 = energy();
  const Vec3 L0 = momentum();
  Real drift = 0, L_drift = 0, violation = 0;
  int iterations = 0;
  for (int k = 0; k < 300; ++k) {
    const NewtonResult r = step_coupled(p, SparseMatrix(), StepRule::energy_momentum, 0.01, run, solver, {.tolerance = 1e-12});
    ASSERT_TRUE(r.converged) << "step " << k << ": " << r.failure;
    iterations += r.iterations;
    drift = std::max(drift, std::abs(energy() - E0) / E0);
    L_drift = std::max(L_drift, (momentum() - L0).norm() / L0.norm());
    violation = std::max(violation, joint_violation(p, run, p.joints[0]));
  }
  std::printf("hinged pair: energy drift %.2e, |L| drift %.2e, joint %.2e, %.2f Newton iterations per step\n", drift, L_drift,
              violation, iterations / 300.0);
  EXPECT_LT(drift, 1e-10);
  EXPECT_LT(L_drift, 1e-10);
  EXPECT_LT(violation, 1e-10);
  EXPECT_LT(iterations, 300 * 6);
}

TEST(FemJoints, SoftBeamPinnedToAFreeBodyKeepsEnergyAndMomenta) {
  // A hex8 rubber beam (0.6 x 0.1 x 0.1 m) whose end node at its axis is joined (spherical) to a
  // free box spinning at 3 rad/s, no gravity: no external force acts on the system, so its energy
  // (kinetic of both + strain) and linear and angular momentum are constant to the Newton
  // tolerance (the joint's rows are linear in u and q: no work, equal and opposite forces), and
  // the joint holds to 1e-10 m, over 200 steps of 0.01 s.
  FemProblem p;
  p.model.dim = 3;
  add_fem_solid(p.model, test::fem_solid("beam", make_box_mesh(Vec3(0, -0.05, -0.05), Vec3(0.6, 0.05, 0.05), {6, 2, 2}, ElementType::hex8),
                                         test::fem_material(HyperelasticModel::neo_hookean, 2e5, 0.3, 1000)));
  finalize_fem_model(p.model);
  FemRigidBody box = box_body("box", Vec3(-0.2, -0.1, -0.1), Vec3(0, 0.1, 0.1), 500);
  box.initial = director_state_at_rest_pose(box.body, Vec3(0, 0, 0), Vec3(0, 0, 3));
  p.rigid_bodies.push_back(box);
  // The beam's node at (0, 0, 0), on the box's face.
  Index node = -1;
  for (Index i = 0; i < p.model.node_count; ++i)
    if (p.model.reference_position(i).norm() < 1e-12) node = i;
  ASSERT_GE(node, 0);
  FemJoint j;
  j.name = "pin";
  j.rows.push_back({FemJointRows::Kind::coincide, body_point(box, 0, Vec3::Zero()), {FemJointEndKind::node, node, Vec3::Zero()}});
  p.joints.push_back(j);
  const SparseMatrix M = assemble_mass_matrix(p.model);
  FemRunState run = start(p);
  // The box spins about its centre; the pinned beam node starts with the box's point velocity.
  run.solids.v.segment<3>(3 * node) = Vec3(0, 0, 3).cross(-box.body.centre);
  SparseLuSolver solver;
  auto totals = [&](Real& energy, Vec3& linear, Vec3& angular) {
    momenta(p.model, run.solids.u, run.solids.v, linear, angular);
    linear += box.body.mass * run.bodies[0].v_phi;
    angular += angular_momentum(box.body, run.bodies[0]);
    energy = kinetic_energy(p.model, run.solids.v) + run.solids.energy + kinetic_energy(box.body, run.bodies[0]);
  };
  Real E0, E;
  Vec3 p0, L0, p1, L1;
  totals(E0, p0, L0);
  Real drift = 0, momentum_drift = 0, violation = 0;
  for (int k = 0; k < 200; ++k) {
    const NewtonResult r = step_coupled(p, M, StepRule::energy_momentum, 0.01, run, solver, {.tolerance = 1e-12});
    ASSERT_TRUE(r.converged) << "step " << k << ": " << r.failure;
    totals(E, p1, L1);
    drift = std::max(drift, std::abs(E - E0) / E0);
    momentum_drift = std::max({momentum_drift, (p1 - p0).norm() / (box.body.mass * 1.0), (L1 - L0).norm() / L0.norm()});
    violation = std::max(violation, joint_violation(p, run, p.joints[0]));
  }
  std::printf("beam pinned to a spinning box: energy drift %.2e, momentum drift %.2e, joint %.2e m, strain energy %.3e J\n",
              drift, momentum_drift, violation, run.solids.energy);
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(momentum_drift, 1e-9);
  EXPECT_LT(violation, 1e-10);
  EXPECT_GT(run.solids.energy, 1e-6 * E0);  // the beam is flung round and bends
}

}  // namespace
}  // namespace moreau
