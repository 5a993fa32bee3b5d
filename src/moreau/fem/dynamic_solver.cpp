#include "moreau/fem/dynamic_solver.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "moreau/fem/fem_assembly.hpp"

namespace moreau {

FemDynamicState initial_dynamic_state(const FemModel& model) {
  FemDynamicState s;
  s.u = VectorX::Zero(model.dof_count());
  s.v = VectorX::Zero(model.dof_count());
  apply_prescribed(model, 0, s.u);
  return s;
}

NewtonResult step_dynamic(const FemModel& model, const SparseMatrix& mass, StepRule rule, Real h,
                          FemDynamicState& state, SparseSymmetricSolver& solver, const NewtonSettings& settings) {
  NewtonResult result;
  const VectorX& u0 = state.u;
  const VectorX& v0 = state.v;
  const VectorX f_ext = external_forces(model, state.time + 0.5 * h);
  VectorX u1 = u0 + h * v0;
  apply_prescribed(model, state.time + h, u1);
  VectorX f;
  SparseMatrix K;
  InternalForceResult cells = timed(result.assembly_s, [&] { return assemble_step_forces(model, u0, u1, rule, f, &K); });
  if (!cells.valid) {
    u1 = u0;
    apply_prescribed(model, state.time + h, u1);
    cells = timed(result.assembly_s, [&] { return assemble_step_forces(model, u0, u1, rule, f, &K); });
    if (!cells.valid) {
      result.failure = fmt::format("cell {} of '{}' is inverted at the start of the step", cells.invalid_cell,
                                   cells.invalid_solid);
      return result;
    }
  }
  const Real c = 2 / (h * h);
  for (;;) {
    const VectorX inertia = mass_times(model, c * (u1 - u0) - (2 / h) * v0);
    const VectorX R = free_part(model, inertia + f - f_ext);
    const Real norm = R.norm();
    result.residual_norms.push_back(norm);
    const Real scale = std::max({inertia.norm(), f.norm(), f_ext.norm(), Real(1e-300)});
    if (norm <= settings.tolerance * scale) break;
    if (result.iterations == settings.max_iterations) {
      result.failure = fmt::format("no convergence in {} Newton iterations (|R| = {:.3e}, scale {:.3e})",
                                   settings.max_iterations, norm, scale);
      return result;
    }
    // dR/du = 2/h^2 M + K_algo: the two matrices share the structure of model.pattern.
    for (Index i = 0; i < K.nonZeros(); ++i) K.valuePtr()[i] += c * mass.valuePtr()[i];
    if (!timed(result.solve_s, [&] { return solver.factorize(K); })) {
      result.failure = "the step's tangent is singular";
      return result;
    }
    const VectorX du = timed(result.solve_s, [&] { return solver.solve(-R); });
    ++result.iterations;
    Real alpha = 1;
    VectorX trial;
    for (int halving = 0;; ++halving, alpha *= 0.5) {
      trial = u1;
      add_free_part(model, alpha * du, trial);
      cells = timed(result.assembly_s, [&] { return assemble_step_forces(model, u0, trial, rule, f, &K); });
      if (cells.valid) break;
      if (halving == settings.max_halvings) {
        result.failure = fmt::format("every Newton correction inverts cell {} of '{}'", cells.invalid_cell,
                                     cells.invalid_solid);
        return result;
      }
    }
    u1 = trial;
    if (alpha * du.norm() <= settings.tolerance * free_part(model, u1 - u0).norm()) {
      const VectorX inertia_end = mass_times(model, c * (u1 - u0) - (2 / h) * v0);
      result.residual_norms.push_back(free_part(model, inertia_end + f - f_ext).norm());
      break;
    }
  }
  result.converged = true;
  result.energy = cells.energy;
  state.v = (2 / h) * (u1 - u0) - v0;
  state.u = u1;
  state.time += h;
  state.energy = cells.energy;
  return result;
}

Real kinetic_energy(const FemModel& model, const VectorX& v) { return 0.5 * v.dot(mass_times(model, v)); }

void momenta(const FemModel& model, const VectorX& u, const VectorX& v, Vec3& linear, Vec3& angular) {
  // p = sum_a (M v)_a and L = sum_a x_a x (M v)_a: the consistent mass couples a node's position
  // with its neighbours' velocities, and (M v)_a collects exactly those products.
  const VectorX Mv = mass_times(model, v);
  linear.setZero();
  angular.setZero();
  for (Index n = 0; n < model.node_count; ++n) {
    Vec3 x = model.reference_position(n), p = Vec3::Zero();
    for (int k = 0; k < model.dim; ++k) {
      x[k] += u[model.dof(n, k)];
      p[k] = Mv[model.dof(n, k)];
    }
    linear += p;
    angular += x.cross(p);
  }
}

}  // namespace moreau
