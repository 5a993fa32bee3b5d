#pragma once
// Time stepping of the Navier-Stokes model: keeps the previous states a scheme needs and starts
// each scheme properly.
//   BDF2 starts with one backward-Euler step (it needs two previous states).
//   The midpoint rule starts with two backward-Euler half steps (Rannacher 1984, "Finite element
//   solution of diffusion problems with irregular data", Numer. Math. 43): it is not L-stable, so
//   initial data that do not satisfy the discrete (PSPG-modified) continuity equation, e.g. an
//   impulsive start, excite stiff modes it barely damps; the damped start keeps second order.
//   (Measured on the Taylor-Green vortex: without it the observed order is erratic, 4-7.)
#include "moreau/fem/flow/navier_stokes.hpp"

namespace moreau {

class ArchiveWriter;
class ArchiveReader;

class FlowStepper {
 public:
  explicit FlowStepper(FlowIntegrator integrator) : integrator_(integrator) {}
  /// A copy keeps its own previous states (its last step points at them, not at the original's):
  /// a step that fails can be undone by assigning back a copy taken before it.
  FlowStepper(const FlowStepper& other) { *this = other; }
  FlowStepper& operator=(const FlowStepper& other);

  /// Advances x (the state at t) to t + dt. On failure x is left at the failed iterate and the
  /// stepper can be discarded. A `source` (an immersed solid) takes part in every solve and
  /// accepts each converged one (the midpoint rule's start is two solves).
  FlowSolveResult step(const NavierStokesModel& model, Real t, Real dt, VectorX& x, FlowLinearSolver& solver,
                       const FlowSolveSettings& settings, FlowSource* source = nullptr);

  /// The last step's scheme (with its previous states), for residual-based probes.
  const FlowTimeStep& last_step() const { return last_; }

  /// Checkpoints: the steps taken, the previous states and the last step's scheme (pointing at
  /// this stepper's previous states again after load).
  void save(ArchiveWriter& out) const;
  void load(ArchiveReader& in);

 private:
  FlowSolveResult single(const NavierStokesModel& model, FlowIntegrator scheme, Real t, Real dt, VectorX& x,
                         FlowLinearSolver& solver, const FlowSolveSettings& settings, FlowSource* source);

  FlowIntegrator integrator_;
  long steps_ = 0;
  VectorX previous_, before_previous_;
  FlowTimeStep last_;
};

}  // namespace moreau
