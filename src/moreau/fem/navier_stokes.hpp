#pragma once
// Incompressible Navier-Stokes on equal-order Q1Q1 elements (quad4 in 2D, hex8 in 3D) stabilized
// by SUPG, PSPG and LSIC (methods.md sec. 10; Tezduyar 1992; Tezduyar & Osawa 2000). Find (u, p)
// with, for all (w, q),
//   int w . rho (du/dt + (grad u) u - f) + int eps(w) : sigma(u, p) + int q div u
//   + sum_e int [tau (u . grad w) + tau/rho grad q] . r_M + sum_e int nu_LSIC rho div w div u = 0,
//   sigma = -p I + 2 mu eps(u),   r_M = rho (du/dt + (grad u) u - f) + grad p
// (the viscous second derivatives of r_M vanish on affine cells and are dropped, as usual for Q1).
// Stabilization parameters at each quadrature point (methods.md, with r = 2):
//   tau = (tau1^-2 + tau2^-2 + tau3^-2)^-1/2,  tau1 = h_UGN / (2|u|) = 1 / sum_a |u . grad N_a|,
//   tau2 = dt / 2 (transient only),  tau3 = h^2 / (4 nu) with h the cell's size (area^(1/2),
//   volume^(1/3)),  tau_PSPG = tau_SUPG = tau,  nu_LSIC = tau |u|^2.
// Newton's method with tau frozen at the current iterate (every other dependence on u, including
// the SUPG test function's, is linearised exactly). Time stepping: backward Euler (dt > 0);
// dt = 0 solves the steady equations. Outflow boundaries without conditions are "do nothing"
// (sigma n = 0 in the symmetric-gradient form).
#include <functional>
#include <vector>

#include "moreau/fem/fem_mesh.hpp"
#include "moreau/fem/fem_model.hpp"
#include "moreau/fem/linear_solver.hpp"
#include "moreau/fem/static_solver.hpp"

namespace moreau {

struct NavierStokesModel {
  FemMesh mesh;                  // quad4 or hex8
  Real density = 1;              // kg/m^3
  Real viscosity = 0.01;         // dynamic, Pa s
  Vec3 body_force = Vec3::Zero();  // per unit mass, m/s^2
  int threads = 0;
  // For tests of the Jacobian only: if > 0, tau and nu_LSIC take these values everywhere (the
  // Jacobian treats them as constants, so with them fixed it is the exact derivative).
  Real fixed_tau = 0, fixed_lsic = 0;
  // Per node: dim velocity components, then the pressure.
  std::vector<PrescribedDof> prescribed;
  // Built by setup_navier_stokes:
  int dim = 2, points = 0;
  std::vector<Real> weight, shape;   // [cell][point], [cell][point][node]
  std::vector<Vec3> gradient;        // [cell][point][node]
  std::vector<Real> cell_size;       // m
  std::vector<std::vector<Index>> colours;
  std::vector<Index> free_index, slots;
  Index free_count = 0;
  SparseMatrix pattern;

  int fields() const { return dim + 1; }
  Index dof_count() const { return mesh.node_count() * fields(); }
  Index dof(Index node, int field) const { return node * fields() + field; }
};

/// Quadrature, colours, the free dofs and the Jacobian's sparsity; after `prescribed` is set.
void setup_navier_stokes(NavierStokesModel& model);

/// The residual on all dofs and, if `J` is given, its Jacobian (tau frozen) on the free dofs, at x
/// (x_old and dt > 0: backward Euler; dt = 0: steady). Cells in parallel by colours, deterministic.
void assemble_flow(const NavierStokesModel& model, const VectorX& x, const VectorX* x_old, Real dt, VectorX& R,
                   SparseMatrix* J);

/// Solves one backward-Euler step from x_old (dt > 0) or the steady equations (dt = 0), starting
/// from x, whose prescribed dofs are set to their values at t. Newton with tau frozen; converged
/// when |R| <= tolerance * |R_0| or the correction is below tolerance * |x|.
NewtonResult solve_navier_stokes(const NavierStokesModel& model, Real t, Real dt, const VectorX& x_old, VectorX& x,
                                 SparseLuSolver& solver, const NewtonSettings& settings = {});

/// Velocity and pressure at a point (the cell containing it is found by inverting the
/// isoparametric map); false if the point is outside the mesh.
bool sample_flow(const NavierStokesModel& model, const VectorX& x, const Vec3& point, Vec3& velocity, Real& pressure);

}  // namespace moreau
