#include "moreau/solvers/nmd/constraint_fluid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/fluids/ambient_air.hpp"
#include "moreau/fluids/density_constraint.hpp"
#include "moreau/fluids/fluid_emitter.hpp"
#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/fluids/fluid_motion.hpp"
#include "moreau/fluids/fluid_neighbors.hpp"
#include "moreau/fluids/fluid_velocity.hpp"
#include "moreau/fluids/fluid_viscosity.hpp"
#include "moreau/fluids/interfacial_tension.hpp"
#include "moreau/fluids/phase_drift.hpp"
#include "moreau/fluids/solid_coupling.hpp"
#include "moreau/fluids/surface_tension.hpp"
#include "moreau/fluids/wall_adhesion.hpp"
#include "moreau/model/model.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

namespace {

// The entry of `end` in the row's ends from `first` on, appended (with a zero Jacobian) if new.
std::size_t find_or_add(std::vector<VelocityEnd>& ends, std::vector<std::array<Real, 6>>& jacobian, std::size_t first,
                        const VelocityEnd& end) {
  for (std::size_t k = first; k < ends.size(); ++k)
    if (ends[k].dof == end.dof) return k;
  ends.push_back(end);
  jacobian.push_back({0, 0, 0, 0, 0, 0});
  return ends.size() - 1;
}

// Speculative reach of a contact row: what particle i can travel in the step, plus a quarter
// radius so resting contacts stay in the system.
Real contact_reach(const Vec3& velocity, const Model& model, Real h) {
  return h * (velocity.norm() + h * model.settings.gravity.norm()) + 0.25 * model.fluid.particle_radius;
}

}  // namespace

void ConstraintFluid::start_step(const Model& model, State& state, Real time, int threads) {
  // Before new particles, with the lists of the last step (drift_phases sizes its own buffers).
  if (model.fluid.phase_drift) drift_phases(model, state.fluid, scratch_, state.step, threads);
  if (!model.fluid.emitters.empty()) emit_fluid(model, state.fluid, time);
}

void ConstraintFluid::prepare(const Model& model, State& state, Real time, int threads) {
  scratch_.fit(model.fluid);
  const bool coupled_solids = model.fluid.solid.size() > 0;
#pragma omp parallel num_threads(threads)
  {
    if (model.fluid.boundary.moving) place_boundary_samples(model, state.fluid, time);
    if (coupled_solids) place_solid_samples(model, state);
    update_fluid_neighbors(model, state.fluid, scratch_, time);
  }
}

void ConstraintFluid::add_rows(const Model& model, State& state, const VelocitySpace& space, Real h, Real end_time,
                               NmdBlockInput& in, NmdSystem& system) {
  const FluidModel& fm = model.fluid;
  FluidState& fluid = state.fluid;
  const Index n = fluid.count;
  // Warm start: the last solve's multiplier, kept in the state as the pressure p = -lambda / V.
  multiplier_.resize(n);
  for (Index i = 0; i < n; ++i) multiplier_[i] = -fluid.pressure[i] * fm.particle_volume * h * h;
  for (Index i = 0; i < n; ++i) add_density_row(model, state, space, i, in, system, h);

  // Walls: C = d(x_i) - r >= 0 for each collider surface within reach (frictionless; the
  // collider's velocity is the part of dC/dt outside the velocity vector).
  const Real r = fm.particle_radius;
  for (Index i = 0; i < n; ++i) {
    const Real reach = contact_reach(fluid.velocity[i], model, h);
    for (const Collider& c : model.colliders) {
      ColliderDistance surfaces[3];
      const int count = collider_surfaces_within(c, c.position_at(end_time - h), fluid.position[i], r + reach, surfaces);
      for (int k = 0; k < count; ++k) {
      const ColliderDistance& d = surfaces[k];
      in.resize(1, 1);
      in.kind = NmdBlockKind::contact;
      in.end[0] = space.fluid_end(i);
      for (int k = 0; k < 3; ++k) in.at(0, 0)[k] = d.normal[k];
      in.C[0] = d.distance - r;
      in.known[0] = -d.normal.dot(c.velocity);
      in.lower[0] = 0;
      in.compliance(0, 0) = model.settings.nmd.contact_compliance;
      system.add(in, space, h, model.settings.nmd);
      }
    }
  }

  // Solid samples: C = |x_i - x_s| - 1.5 r >= 0 on the fluid particle and the sample's solid.
  const FluidSolidSamples& samples = fm.solid;
  const Real closest = fm.solid_contact_distance;
  for (Index i = 0; i < n; ++i) {
    const Index* row = fluid.solid_neighbors.row(i);
    const Real reach = contact_reach(fluid.velocity[i], model, h);
    for (Index e = 0; e < fluid.solid_neighbors.count[i]; ++e) {
      const Index s = row[e];
      const Vec3 offset = fluid.position[i] - fluid.solid_position[s];
      const Real distance = offset.norm();
      if (distance - closest >= reach || distance < 1e-9 * closest) continue;
      const Vec3 normal = offset / distance;
      const Index body = samples.body[s];
      in.resize(1, body >= 0 ? 2 : 5);
      in.kind = NmdBlockKind::contact;
      in.end[0] = space.fluid_end(i);
      for (int k = 0; k < 3; ++k) in.at(0, 0)[k] = normal[k];
      if (body >= 0) {
        in.end[1] = space.end(BodyEnd{BodyEndKind::body, body});
        const Vec3 angular = (fluid.solid_position[s] - state.rigid.position[body]).cross(normal);
        for (int k = 0; k < 3; ++k) {
          in.at(0, 1)[k] = -normal[k];
          in.at(0, 1)[3 + k] = -angular[k];
        }
      } else {
        for (int slot = 0; slot < 4; ++slot) {
          const Real weight = samples.weight[s][slot];
          if (weight == 0) continue;  // the world's end: no entries
          in.end[1 + slot] = space.particle_end(samples.particle[s][slot]);
          for (int k = 0; k < 3; ++k) in.at(0, 1 + slot)[k] = -weight * normal[k];
        }
      }
      in.C[0] = distance - closest;
      in.lower[0] = 0;
      in.compliance(0, 0) = model.settings.nmd.contact_compliance;
      system.add(in, space, h, model.settings.nmd);
    }
  }
}

void ConstraintFluid::add_density_row(const Model& model, State& state, const VelocitySpace& space, Index i,
                                      NmdBlockInput& in, NmdSystem& system, Real h) {
  const FluidModel& fm = model.fluid;
  FluidState& fluid = state.fluid;
  const FluidSolidSamples& samples = fm.solid;
  const DensityEvaluation density = evaluate_density_constraint(fm, fluid, scratch_.solid_inv_mass.data(), i);
  const FluidPhase& phase = fm.phases[fluid.phase[i]];
  fluid.density[i] = phase.rest_density * (1 + density.C);

  row_end_.assign(1, space.fluid_end(i));
  row_jacobian_.assign(1, {density.gradient.x(), density.gradient.y(), density.gradient.z(), 0, 0, 0});
  std::size_t first_solid = 0;
  for_each_density_gradient(fm, fluid, i, [&](DensityNeighbor kind, Index j, const Vec3& g) {
    if (kind == DensityNeighbor::fluid) {
      row_end_.push_back(space.fluid_end(j));
      row_jacobian_.push_back({g.x(), g.y(), g.z(), 0, 0, 0});
      first_solid = row_end_.size();
      return;
    }
    const Index body = samples.body[j];
    if (body >= 0) {  // x_s = x_b + R s: (g, (x_s - x_b) x g) on the body
      const std::size_t k = find_or_add(row_end_, row_jacobian_, first_solid, space.end(BodyEnd{BodyEndKind::body, body}));
      const Vec3 angular = (fluid.solid_position[j] - state.rigid.position[body]).cross(g);
      for (int c = 0; c < 3; ++c) {
        row_jacobian_[k][c] += g[c];
        row_jacobian_[k][3 + c] += angular[c];
      }
      return;
    }
    for (int slot = 0; slot < 4; ++slot) {  // x_s = sum_k b_k x_k: b_k g on particle k
      const Real weight = samples.weight[j][slot];
      if (weight == 0) continue;
      const std::size_t k = find_or_add(row_end_, row_jacobian_, first_solid, space.particle_end(samples.particle[j][slot]));
      for (int c = 0; c < 3; ++c) row_jacobian_[k][c] += weight * g[c];
    }
  });

  in.resize(1, static_cast<int>(row_end_.size()));
  in.kind = NmdBlockKind::bounded;
  for (std::size_t k = 0; k < row_end_.size(); ++k) {
    in.end[k] = row_end_[k];
    std::copy(row_jacobian_[k].begin(), row_jacobian_[k].end(), in.at(0, static_cast<int>(k)));
  }
  in.C[0] = density.C;
  in.compliance(0, 0) = phase.compliance;
  in.lower[0] = -kInfinity;
  in.upper[0] = 0;  // pushes only
  in.memory = &multiplier_[i];
  in.memory_rows = 1;
  system.add(in, space, h, model.settings.nmd);
}

void ConstraintFluid::store_pressure(const Model& model, State& state, Real h) {
  const Real scale = -1 / (model.fluid.particle_volume * h * h);
  for (Index i = 0; i < state.fluid.count; ++i) state.fluid.pressure[i] = scale * multiplier_[i];
}

void ConstraintFluid::integrate(const Model& model, State& state, Real h, Real time) {
  FluidState& fluid = state.fluid;
  const Real r = model.fluid.particle_radius;
  for (Index i = 0; i < fluid.count; ++i) {
    Vec3 x = fluid.position[i] + h * fluid.velocity[i];
    if (fluid.inv_mass[i] != 0)  // a kinematic particle (solid, or held in a nozzle) stays on its course
      for (const Collider& c : model.colliders) x = keep_clear_of_collider(c, c.position_at(time), x, r);
    fluid.position[i] = x;
  }
}

void ConstraintFluid::finish_step(const Model& model, State& state, Real dt, Real h, int threads) {
#pragma omp parallel num_threads(threads)
  {
    apply_implicit_fluid_viscosity(model, state, scratch_, dt);
    apply_fluid_velocity_corrections(model, state.fluid, scratch_, dt);
    apply_ambient_air(model, state.fluid, dt);
    apply_fluid_surface_tension(model, state.fluid, scratch_, dt);
    apply_fluid_wall_adhesion(model, state.fluid, dt, state.time + dt);
    apply_fluid_interfacial_tension(model, state.fluid, scratch_, dt);
    apply_fluid_heat(model, state.fluid, scratch_, dt);
  }
  fluid_cfl_number(model, state.fluid, h);
}

}  // namespace moreau
