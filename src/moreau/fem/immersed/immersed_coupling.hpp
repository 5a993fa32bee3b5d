#pragma once
// The immersed solids' momentum source in the fluid (the seed paper's "Interaction between fluid
// and structure"; Zhang, Gerstenberger, Wang & Liu 2004, "Immersed finite element method", CMAME
// 193; Wang, Jimack & Walkley 2017, "A one-field monolithic fictitious domain method for
// fluid-structure interactions", CMAME 317, for the interpolation with the fluid's own shape
// functions and its energy argument).
//
// The fluid fills the whole domain B and the solid occupies B_s. The fluid's momentum balance
// gets, inside B_s, the force F = (rho_f - rho_s)(dv/dt - b) + div(sigma_s - sigma_f~), so that
// there the balance is the solid's own, rho_s (dv/dt - b) = div sigma_s + div(fluid stress kept).
// Tested with the fluid's shape functions N_A, the terms added to the fluid's residual at node A are
//   R_A += sum_C N_A(x_C) r_C,
//   r_C  = int_B0 P(F) grad_X N~_C dV                                  (elastic: the solid's nodal force)
//        + int_B0 J 2 (mu_s - mu_f) d(V) F^-T grad_X N~_C dV            (viscous difference)
//        + sum_D M~_CD ((V_D,n+1 - V_D,n)/dt - b)                     (inertia difference, M~ with rho_s - rho_f)
// where C, D run over the solid's nodes, N~ are the solid's shape functions on its reference
// configuration B0, x_C the node's current position and V its velocity: the solid has no momentum
// equation of its own, its nodes move with the fluid's velocity interpolated at them,
//   V_C = sum_A N_A(x_C) v_A                    (the IFEM mapping I(v) of the seed),
// so that the same matrix M_CA = N_A(x_C) maps velocities to the solid and forces to the fluid,
// and the power the fluid spends on the solid, v . M^T r, is exactly r . V.
// The stabilization (SUPG, PSPG) of the fluid's cells sees this force as a nodal density: each
// fluid node's share over its lumped volume joins their strong momentum residual, with its exact
// derivative (flow_source_assembly.hpp). Where the solid holds the fluid, PSPG then does not read
// the holding force as an error of the pressure gradient and let the fluid through the solid (a
// released disc's added mass was a third of potential flow's without it). (Testing the nodal
// forces with the stabilized test functions instead puts grad N_A at the solid's nodes, which
// jumps when a node crosses a fluid cell's edge, and Newton stalled on it.)
//
// What is kept of the fluid's stress inside the solid (sigma_f~): the pressure, always. It is the
// multiplier of the fluid's continuity equation, which holds over the whole domain, and the pressure
// is shared (the immersed structural potential method of Gil, Arranz Carreno, Bonet & Hassan 2010,
// JCP 229, does the same). That would make the solid's motion incompressible, but it does not
// for a solid with cells about the fluid's size (why is not established; its resting place does not
// depend on PSPG's tau, which a leak through the solid at a rate set by tau would not change
// either): measured, Turek & Hron's bar (nu = 0.4) under a static load bends and changes volume as
// it does alone, within 0.3 % (docs/validation.md). The fluid's
// viscous stress is replaced by the solid's own, 2 mu_s d: with the default mu_s = mu_f the solid is
// a Kelvin-Voigt material with the fluid's viscosity and nothing is subtracted; mu_s = 0 removes
// the fluid's viscous stress from the solid entirely, as the seed's formula writes.
//
// Time (the fluid's scheme with theta = 1/2, the midpoint rule, or 1, backward Euler): with
// v_theta = theta v_n+1 + (1 - theta) v_n,
//   u_n+1 = u_n + dt V_theta,   V_theta = M(x*) v_theta,   V_n+1 = M(x*) v_n+1,
//   x* = X + u_n + theta (u_n+1 - u_n)          (the solid at t_n+theta),
// a fixed point in x* solved to round-off in every evaluation (it contracts by about
// theta dt |grad v|). The elastic force is Gonzalez's discrete gradient between u_n and u_n+1 for
// the midpoint rule (solid_element_step, energy_momentum), so r_elastic . (u_n+1 - u_n) =
// W(u_n+1) - W(u_n) exactly and the solid's stored energy enters the fluid's energy balance without
// error; for backward Euler it is the force at u_n+1. The viscous term is evaluated at x* with
// V_theta.
//
// Jacobian: exact, including the motion of the solid's nodes inside the fluid's cells during the
// iterations (which moves both the mapping M(x*) and where the forces are spread; derivation in
// add_jacobian), except for the viscous difference, whose F is frozen at the current x*. The
// fluid's velocity gradient at the nodes enters through (I - theta dt grad v)^-1; the derivatives
// of the shape functions jump where a node crosses a fluid cell's edge, so the residual is only
// piecewise smooth there. Measured on the two-leaflet channel (1 ms steps, tolerance 1e-8): 3.6
// Newton iterations per step, quadratic at the end, against 5.3 and linear convergence when
// M(x*) was lagged (frozen at the current x*, the Jacobian M^T (d r / d V) M alone); 2.5 ms
// steps converge in 5.3 iterations, 5 ms steps fail after about 0.05 s (Newton's first
// corrections invert the thin leaflets' cells).
//
// Dirichlet conditions of a solid (a clamped base) prescribe its displacement: those components
// follow u(t) instead of the fluid, and their nodal forces (the reactions) are not spread.
//
// Rigid bodies (immersed_rigid_body.hpp) are solids whose nodes follow their frame instead of the
// fluid: this coupling leaves their nodes to ImmersedRigidCoupling and adds its forces.
#include <optional>
#include <vector>

#include "moreau/fem/core/mesh_locator.hpp"
#include "moreau/fem/flow/navier_stokes.hpp"
#include "moreau/fem/immersed/immersed_rigid_body.hpp"
#include "moreau/fem/immersed/immersed_solids.hpp"

namespace moreau {

/// Where a step leaves the solids: positions, velocities and the fluid cells they lie in.
struct ImmersedKinematics {
  VectorX displacement;   // u_n+1, per solid dof
  VectorX velocity;       // V_n+1
  VectorX velocity_theta; // V_theta
  std::vector<MeshPoint> located;  // per solid node: the fluid cell at x* (cell -1 for a clamped node)
};

class ImmersedCoupling final : public FlowSource {
 public:
  /// Keeps references to the fluid, the solids and the state, which must outlive the coupling;
  /// `state` is advanced by accept().
  ImmersedCoupling(const NavierStokesModel& fluid, const ImmersedSolids& solids, ImmersedSolidState& state);

  void add(const VectorX& x, const FlowTimeStep& step, VectorX& R, std::vector<Eigen::Triplet<Real, int>>* jacobian,
           FlowLowRank* low_rank = nullptr) const override;
  void accept(const VectorX& x, const FlowTimeStep& step) override;
  std::string last_failure() const override { return last_failure_; }

  /// The solids' kinematics at fluid state x of `step` (throws NumericalError if a solid node
  /// leaves the fluid's mesh).
  ImmersedKinematics kinematics(const VectorX& x, const FlowTimeStep& step) const;

 private:
  // The deformable solids' nodal forces at k (see the .cpp); false if a solid cell is inverted.
  bool nodal_forces(const ImmersedKinematics& k, Real theta, Real dt, VectorX& r,
                    std::vector<Eigen::Triplet<Real, int>>* by_theta_velocity,
                    std::vector<Eigen::Triplet<Real, int>>* by_next_velocity) const;
  // The fluid's force on deformable solid s over the step ending at k, given its nodal forces r.
  Vec3 fluid_force_on_solid(size_t s, const ImmersedKinematics& k, const VectorX& r, Real dt) const;
  // M: V = M v, per free solid dof and fluid velocity dof (all, or only the free ones), N_A(x_C).
  SparseMatrix velocity_map(const ImmersedKinematics& k, bool free_columns) const;
  // The source's Jacobian in the fluid's free velocities (see the .cpp), given the solid force r
  // and its per-dof derivatives in V_theta and V_n+1.
  void add_jacobian(const ImmersedKinematics& k, const VectorX& x, const VectorX& x_n, Real theta, Real dt,
                    const VectorX& r, const std::vector<Eigen::Triplet<Real, int>>& by_theta_velocity,
                    const std::vector<Eigen::Triplet<Real, int>>& by_next_velocity,
                    std::vector<Eigen::Triplet<Real, int>>& jacobian) const;

  const NavierStokesModel& fluid_;
  const ImmersedSolids& solids_;
  ImmersedSolidState& state_;
  MeshLocator locator_;
  ImmersedRigidCoupling rigid_;
  std::vector<char> rigid_node_;  // per solid node: it belongs to a rigid body
  mutable std::string last_failure_;  // why the last add() gave an infinite residual
};

/// The solids' stored elastic energy at their current displacement, J (2D: J/m).
Real immersed_elastic_energy(const ImmersedSolids& solids, const ImmersedSolidState& state);

/// The kinetic energy the solids add to the fluid's, 1/2 V^T M~ V with M~ the mass of
/// rho_s - rho_f, J (2D: J/m).
Real immersed_excess_kinetic_energy(const ImmersedSolids& solids, const NavierStokesModel& fluid,
                                    const ImmersedSolidState& state);

}  // namespace moreau
