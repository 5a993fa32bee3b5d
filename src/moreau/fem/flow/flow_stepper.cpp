#include "moreau/fem/flow/flow_stepper.hpp"

#include <stdexcept>

#include "moreau/io/binary_archive.hpp"

namespace moreau {

FlowSolveResult FlowStepper::single(const NavierStokesModel& model, FlowIntegrator scheme, Real t, Real dt, VectorX& x,
                                    FlowLinearSolver& solver, const FlowSolveSettings& settings, FlowSource* source) {
  before_previous_ = previous_.size() ? previous_ : x;
  previous_ = x;
  last_ = {scheme, dt, &previous_, &before_previous_};
  FlowSolveResult result = solve_navier_stokes(model, t + dt, last_, x, solver, settings, source);
  if (result.converged && source) source->accept(x, last_);
  return result;
}

FlowSolveResult FlowStepper::step(const NavierStokesModel& model, Real t, Real dt, VectorX& x, FlowLinearSolver& solver,
                                  const FlowSolveSettings& settings, FlowSource* source) {
  if (integrator_ == FlowIntegrator::steady) {
    if (source) throw std::logic_error("FlowStepper: a source (an immersed solid) needs a transient integrator");
    last_ = {};
    return solve_navier_stokes(model, t, last_, x, solver, settings);
  }
  const bool first = steps_++ == 0;
  if (first && integrator_ == FlowIntegrator::midpoint) {
    FlowSolveResult a = single(model, FlowIntegrator::backward_euler, t, dt / 2, x, solver, settings, source);
    if (!a.converged) return a;
    const FlowSolveResult b = single(model, FlowIntegrator::backward_euler, t + dt / 2, dt / 2, x, solver, settings, source);
    a.converged = b.converged;
    a.failure = b.failure;
    a.iterations += b.iterations;
    a.picard_iterations += b.picard_iterations;
    a.assembly_s += b.assembly_s;
    a.solve_s += b.solve_s;
    a.source_s += b.source_s;
    return a;
  }
  const FlowIntegrator scheme = first && integrator_ == FlowIntegrator::bdf2 ? FlowIntegrator::backward_euler : integrator_;
  return single(model, scheme, t, dt, x, solver, settings, source);
}

FlowStepper& FlowStepper::operator=(const FlowStepper& other) {
  if (this == &other) return *this;
  integrator_ = other.integrator_;
  steps_ = other.steps_;
  previous_ = other.previous_;
  before_previous_ = other.before_previous_;
  last_ = other.last_;
  if (last_.previous) last_.previous = &previous_;
  if (last_.before_previous) last_.before_previous = &before_previous_;
  return *this;
}

void FlowStepper::save(ArchiveWriter& out) const {
  archive(out, std::tie(steps_, previous_, before_previous_, last_.integrator, last_.dt));
}

void FlowStepper::load(ArchiveReader& in) {
  auto fields = std::tie(steps_, previous_, before_previous_, last_.integrator, last_.dt);
  unarchive(in, fields);
  const bool transient = last_.integrator != FlowIntegrator::steady;
  last_.previous = transient ? &previous_ : nullptr;
  last_.before_previous = transient ? &before_previous_ : nullptr;
}

}  // namespace moreau
