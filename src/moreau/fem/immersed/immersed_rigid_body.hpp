#pragma once
// Rigid bodies immersed in a FEM fluid: director frames (the FEM engine's rigid bodies, Betsch &
// Steinmann 2001) coupled to the fluid through a regularized velocity constraint over the body.
//
// A body's motion is x(X, t) = phi(t) + sum_i xi_i d_i(t), xi = X - centre, with the frame
// q = (phi, d_1 .. d_dim) (dim (dim + 1) numbers) and the internal constraints d_i . d_j = delta_ij.
// Its velocity field is linear in dq/dt: at node C of its mesh, V_C = Q_C dq/dt with
// Q_C = [I, xi_1 I, ..., xi_dim I]; its kinetic energy is 1/2 dq^T M dq with M = sum_CD M~_CD Q_C^T Q_D
// (the mesh's consistent mass: exact for the affine field, whatever the body's shape).
//
// The fluid fills the body too. Inside, its velocity is held to the body's by a force density
// (the regularized form of the distributed Lagrange multiplier of Glowinski, Pan, Hesla & Joseph
// 1999, "A distributed Lagrange multiplier/fictitious domain method for particulate flows",
// Int. J. Multiphase Flow 25; the constraint's compliance is 1/k):
//   lambda = k (I(v) - V)        on the body, N/m^3,
// acting as -lambda on the fluid and +lambda on the body, with I(v) the fluid's velocity at the
// body's points (the immersed solids' mapping, immersed_coupling.hpp). At the body's nodes with
// their lumped volumes W_C, lambda_C = k W_C (sum_A N_A(x_C) v_A - Q_C dq/dt), and
//   fluid:  R_A += sum_C N_A(x_C) lambda_C,
//   body:   M_e (dq_n+1 - dq_n)/dt - M_e (b, 0, ..) + G(q_theta)^T mu - sum_C Q_C^T lambda_C = 0,
//           g(q_n+1) = 0,
// where M_e is the frame's mass for rho_s - rho_f (the fluid inside carries the rest of the
// body's inertia and weight), b the gravity and mu the internal constraints' multipliers. Time
// follows the fluid's theta scheme: dq_theta = theta dq_n+1 + (1 - theta) dq_n,
// q_n+1 = q_n + dt dq_theta, the body's points at q_theta = q_n + theta dt dq_theta, and the slip
// at theta. With the midpoint rule G(q_theta) (q_n+1 - q_n) = g(q_n+1) - g(q_n) = 0 (g is
// quadratic), so the multipliers do no work, and the coupling dissipates
// dt sum_C k W_C |slip_C|^2 >= 0: fluid plus body energy cannot grow.
//
// The slip is O(force density / k); where the body holds the fluid against a viscous stress jump
// at its surface the density is about mu |dv/dx| / h, so the slip relative to the body's speed U
// over a size R is about mu / (k h R). The default k = 1000 (rho_f / dt + mu_f / h^2) (h the
// smallest fluid cell) makes it about 1e-3 h / R, and keeps the Jacobian's entries within 1e4 of
// the fluid's own, which the direct solvers handle without loss. The body's nodes are where the
// constraint acts: its mesh should be at least as fine as the fluid's (between its nodes the fluid
// is not held).
//
// For given fluid velocities the frame (dq_n+1, mu) solves the body's equations, by Newton's
// method (their Jacobian includes the motion of the body's points in the fluid's cells). The
// fluid's Jacobian is then exact: the direct term theta M^T K M plus the frame's response,
// dR/dv = dR/dv|_q + dR/d(dq) d(dq)/dv with d(dq)/dv from the implicit function theorem (a dense
// block over the fluid dofs around the body, of rank dim (dim + 1)).
//
// A driven body (its `motion` set: a rigid paddle, a rotor, an obstacle held still) follows its
// prescribed motion instead (prescribed_rigid_motion.hpp); its frame does not depend on the fluid,
// and its only Jacobian term is the direct one. Either kind records, at each accepted step, the
// force and torque the fluid exerted on it (fluid_load in the source has the balance they come from).
#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "moreau/fem/core/mesh_locator.hpp"
#include "moreau/fem/flow/navier_stokes.hpp"
#include "moreau/fem/immersed/immersed_solids.hpp"

namespace moreau {

/// The frame of a body at rest in its reference pose: phi = centre, d_i = e_i.
VectorX rigid_frame_at_rest(const ImmersedRigidBody& body, int dim);

/// A rigid body's frame data from its mesh (model.solids[solid], density rho_s, added with its
/// consistent mass) in a fluid of density rho_f: centre of mass, excess mass and nodal volumes,
/// coupled with stiffness k (Pa s/m^2).
ImmersedRigidBody make_immersed_rigid_body(const FemModel& model, Index solid, Real fluid_density, Real coupling_stiffness);

/// The default coupling stiffness k = 1000 (rho_f / dt + mu_f / h^2), h the smallest fluid cell.
Real default_rigid_coupling_stiffness(const NavierStokesModel& fluid, Real dt);

/// Angular velocity (world; 2D: about z) of a frame: w = 1/2 sum_i d_i x dd_i/dt.
Vec3 rigid_frame_angular_velocity(const VectorX& frame, const VectorX& frame_velocity, int dim);

class ImmersedRigidCoupling {
 public:
  /// Keeps references to the fluid, the solids and the locator, which must outlive it.
  ImmersedRigidCoupling(const NavierStokesModel& fluid, const ImmersedSolids& solids, const MeshLocator& locator)
      : fluid_(fluid), solids_(solids), locator_(locator),
        smallest_cell_(*std::min_element(fluid.cell_size.begin(), fluid.cell_size.end())) {}

  /// Adds the bodies' forces on the fluid at x to R and, if `jacobian` is given, their Jacobian on
  /// the fluid's free dofs: the frame's response (rank dim (dim + 1) per body) goes to `low_rank`
  /// if given, else into the triplets as a dense block. Returns an empty string, or why a body's
  /// frame has no solution (a node outside the fluid's mesh, or its Newton iterations failed).
  std::string add(const VectorX& x, const FlowTimeStep& step, Real theta, const ImmersedSolidState& state, VectorX& R,
                  std::vector<Eigen::Triplet<Real, int>>* jacobian, FlowLowRank* low_rank = nullptr) const;

  /// Advances the bodies' frames and their nodes' displacements and velocities to the end of a
  /// converged step at x, and records the fluid's force and torque on each body over the step
  /// (throws NumericalError naming the body if a frame has no solution).
  void accept(const VectorX& x, const FlowTimeStep& step, Real theta, ImmersedSolidState& state) const;

 private:
  struct BodyStep;
  bool evaluate_nodes(size_t b, const VectorX& x, const VectorX& x_n, Real theta, const VectorX& q_theta, BodyStep& s,
                      std::string& failure) const;
  std::pair<Vec3, Vec3> fluid_load(size_t b, const BodyStep& s, Real dt, Real theta, const ImmersedSolidState& state) const;
  std::optional<BodyStep> solve_frame(size_t b, const VectorX& x, const FlowTimeStep& step, Real theta,
                                      const ImmersedSolidState& state, std::string& failure) const;

  const NavierStokesModel& fluid_;
  const ImmersedSolids& solids_;
  const MeshLocator& locator_;
  Real smallest_cell_;  // m, the scale of the frame's convergence test
};

}  // namespace moreau
