// The constraint engine as the run loop sees it: the scene's registered Solver (settings.solver)
// stepping its Model and State; probes, frames and run.json fields of particles, rigid bodies,
// fluids and the constraint families.
#include "moreau/run/engines.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <optional>

#include "moreau/fluids/fluid_viscosity.hpp"
#include "moreau/fluids/friction_stability.hpp"
#include "moreau/io/binary_archive.hpp"
#include "moreau/io/frame_writer.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/model/diagnostics.hpp"
#include "moreau/run/state_arrays.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/solvers/stage_timer.hpp"

namespace moreau {

namespace {

class ConstraintEngine final : public Engine {
 public:
  explicit ConstraintEngine(Scene& scene) : scene_(scene), model_(scene.model), state_(scene.state) {}

  double time() const override { return state_.time; }
  double dt() const override { return model_.settings.dt; }
  int requested_threads() const override { return model_.settings.threads; }

  void step(int threads) override { scene_.formulation->step(model_, state_, timer_, threads); }

  std::vector<std::string> probe_columns() const override {
    return probe_table_columns(scene_.probes, [](const Probe& p) { return moreau::probe_columns(p); });
  }
  void sample_probes(std::vector<Real>& values) const override {
    for (const Probe& p : scene_.probes) evaluate_probe(p, model_, state_, values);
  }

  void open_frames(const std::string& out_dir, const std::string& scene_name, FrameSeries resume) override {
    frames_.emplace(model_, out_dir, scene_name, scene_.output.formats, std::move(resume));
  }
  void write_frame() override { frames_->write(state_); }
  FrameSeries frame_series() const override { return frames_ ? frames_->series() : FrameSeries{}; }

  // Every solver keeps what carries over from step to step in the State (solver.hpp).
  void save_state(ArchiveWriter& out) const override { archive(out, state_); }
  void load_state(ArchiveReader& in) override { unarchive(in, state_); }

  void add_run_fields(nlohmann::json& j, bool completed) const override;
  std::vector<std::string> warnings() const override;
  std::string summary() const override;

  std::string name() const override { return scene_.solver; }
  std::vector<WorldObject> objects() const override;
  std::vector<StateArray> state_arrays() override;
  std::map<std::string, double> stage_times() const override {
    std::map<std::string, double> times;
    const std::vector<std::string> names = scene_.formulation->stage_names();
    for (int s = 0; s < static_cast<int>(names.size()); ++s) times[names[s]] = timer_.seconds(s);
    return times;
  }

 private:
  Scene& scene_;
  const Model& model_;
  State& state_;
  StageTimer timer_;
  std::optional<FrameWriter> frames_;
};

void ConstraintEngine::add_run_fields(nlohmann::json& j, bool completed) const {
  const Model& m = model_;
  j["substeps"] = m.settings.substeps;
  j["iterations"] = m.settings.iterations;
  nlohmann::json constraints = nlohmann::json::object();
  for_each_family(m.constraints, [&](const auto& family, int) { constraints[std::string(family.kName)] = family.size(); });
  j["counts"] = {{"particles", m.particle_count()},
                 {"fluid_particles", state_.fluid.count},
                 {"objects", m.objects.size()},
                 {"colliders", m.colliders.size()},
                 {"rigid_bodies", std::count_if(m.objects.begin(), m.objects.end(),
                                                [](const ObjectInfo& o) { return o.kind == ObjectKind::rigid_body; })},
                 {"rods", m.rods.size()},
                 {"joints", m.joints.size()},
                 {"constraints", constraints}};
  nlohmann::json stages = nlohmann::json::object();
  const std::vector<std::string> names = scene_.formulation->stage_names();
  for (int s = 0; s < static_cast<int>(names.size()); ++s) stages[names[s]] = timer_.seconds(s);
  j["stage_time_s"] = stages;
  if (!m.fluid.empty())
    j["fluid"] = {{"neighbor_list_builds", state_.fluid.list_builds},
                  {"max_cfl_number", state_.fluid.max_cfl},
                  {"cfl_limit", m.fluid.cfl_limit},
                  {"steps_over_cfl_limit", state_.fluid.cfl_violations},
                  {"wall_samples", m.fluid.boundary.size()}};
  if (!m.fluid.empty() && fluid_has_viscosity(m)) {
    const ViscositySolveStats& v = state_.fluid.viscosity_stats;
    const bool implicit = m.fluid.viscosity_solver == ViscositySolver::implicit_solve;
    j["fluid"]["viscosity"] = {{"solver", implicit ? "implicit" : "explicit"}};
    if (implicit)
      j["fluid"]["viscosity"].update({{"solves", v.solves},
                                      {"mean_iterations", v.solves > 0 ? static_cast<Real>(v.iterations) / v.solves : 0.0},
                                      {"most_iterations", v.most_iterations},
                                      {"unconverged_steps", v.unconverged},
                                      {"worst_relative_residual", v.worst_residual}});
  }
  if (completed)
    j["final_energy_j"] = {{"kinetic", kinetic_energy(m, state_, -1)},
                           {"potential", potential_energy(m, state_, -1)},
                           {"elastic", elastic_energy(m, state_, -1)}};
}

std::vector<std::string> ConstraintEngine::warnings() const {
  std::vector<std::string> out;
  if (state_.fluid.cfl_violations > 0)
    out.push_back(fmt::format(
        "the fluid CFL number max|v| h / (2 r) reached {:.2f} (limit {}) in {} steps; the time step is too long for "
        "the fastest particles: lower settings.dt or raise settings.substeps",
        state_.fluid.max_cfl, model_.fluid.cfl_limit, state_.fluid.cfl_violations));
  const ViscositySolveStats& viscosity = state_.fluid.viscosity_stats;
  if (viscosity.unconverged > 0)
    out.push_back(fmt::format(
        "the implicit fluid viscosity stopped at settings.fluid.viscosity_iterations = {} in {} solves (relative residual "
        "up to {:.2g}, tolerance {:.2g}); raise the iteration limit or the tolerance",
        model_.fluid.viscosity_max_iterations, viscosity.unconverged, viscosity.worst_residual,
        model_.fluid.viscosity_tolerance));
  const Real viscosity_step = scene_.solver == "nmd" ? model_.settings.dt : model_.settings.dt / model_.settings.substeps;
  for (const GrippingSolid& solid : light_gripping_solids(model_, viscosity_step))
    out.push_back(fmt::format(
        "'{}' grips the particle fluid (\"fluid_friction\") but its surface weighs {:.3g} kg/m^2, less than the {:.3g} "
        "kg/m^2 of liquid it drags in one viscosity step (rho0 sqrt(nu h); twice that for a sheet wetted on both sides): "
        "its viscous reaction may fling it about; make it heavier or shorten the step",
        solid.name, solid.surface_density, solid.dragged_density));
  // Adhesion is a bound of the velocity-level contact rows; the position-level solver has none.
  if (scene_.solver != "nmd") {
    std::string glued;
    for (const ObjectInfo& o : model_.objects)
      if (o.adhesion > 0) glued += (glued.empty() ? "'" : ", '") + o.name + "'";
    if (!glued.empty())
      out.push_back(fmt::format("the \"adhesion\" of {} acts only under \"solver\": \"nmd\"; under \"{}\" its contacts "
                                "push and never pull",
                                glued, scene_.solver));
  }
  return out;
}

const char* kind_name(ObjectKind kind) {
  static const char* kinds[] = {"collider", "cloth", "soft_body", "fluid", "rigid_body", "rod", "granular", "shape_matched", "continuum"};
  return kinds[static_cast<int>(kind)];
}

std::vector<WorldObject> ConstraintEngine::objects() const {
  std::vector<WorldObject> list;
  for (const ObjectInfo& o : model_.objects) {
    WorldObject w{o.name, kind_name(o.kind)};
    if (o.has_particles()) {
      w.first = o.particle_begin;
      w.count = o.particle_count();
    } else if (o.has_bodies()) {
      w.first = o.body;
      w.count = o.body_count;
    } else if (o.kind == ObjectKind::fluid) {
      for (Index i = 0; i < state_.fluid.count; ++i) w.count += state_.fluid.phase[i] == o.fluid_phase;
    }
    list.push_back(std::move(w));
  }
  return list;
}

std::vector<StateArray> ConstraintEngine::state_arrays() {
  const long particles = model_.particle_count(), bodies = model_.rigid.count(), fluid = state_.fluid.count;
  RigidBodyState& rb = state_.rigid;
  FluidState& f = state_.fluid;
  // Fluid positions are read only: the neighbour lists are kept across steps while particles
  // stay within their skin, which a moved particle would leave unnoticed.
  return {state_array("particle.position", "m", state_.position, particles, true),
          state_array("particle.velocity", "m/s", state_.velocity, particles, true),
          state_array("particle.angular_velocity", "rad/s", state_.angular_velocity, particles, true),
          state_array("body.position", "m", rb.position, bodies, true),
          state_array("body.orientation", "", rb.orientation, bodies, true),
          state_array("body.velocity", "m/s", rb.velocity, bodies, true),
          state_array("body.angular_velocity", "rad/s", rb.angular_velocity, bodies, true),
          state_array("fluid.position", "m", f.position, fluid, false),
          state_array("fluid.velocity", "m/s", f.velocity, fluid, true),
          state_array("fluid.density", "kg/m^3", f.density, fluid, false),
          state_array("fluid.pressure", "Pa", f.pressure, fluid, false),
          // The enthalpy sets a particle's viscosity and solid state, which the heat stage derives
          // from it once per step: read only. The smoke concentration is a marker: writable.
          state_array("fluid.enthalpy", "J/kg", f.enthalpy, fluid, false),
          state_array("fluid.smoke", "", f.smoke, fluid, true)};
}

std::string ConstraintEngine::summary() const {
  const Model& m = model_;
  std::string s = fmt::format("scene '{}' ({}): solver {}, dt {} s, {} substeps x {} iterations, duration {} s\n",
                              scene_.name, scene_.file, scene_.solver, m.settings.dt, m.settings.substeps,
                              m.settings.iterations, scene_.duration);
  for (const auto& o : m.objects) {
    s += fmt::format("  {:<10} {:<16}", kind_name(o.kind), o.name);
    if (o.kind == ObjectKind::fluid) {
      Index count = 0;
      for (Index p : m.fluid.initial_phase) count += p == o.fluid_phase;
      s += fmt::format(" {} particles of radius {} m, rest density {} kg/m^3", count, m.fluid.particle_radius,
                       m.fluid.phases[o.fluid_phase].rest_density);
    }
    if (o.kind == ObjectKind::rigid_body) {
      static const char* shapes[] = {"sphere", "box", "capsule", "cylinder", "convex hull", "plane"};
      static const char* motions[] = {"dynamic", "fixed", "kinematic"};
      const RigidBodyModel& r = m.rigid;
      s += fmt::format(" {} {}, mass {:.6g} kg, principal inertia ({:.4g}, {:.4g}, {:.4g}) kg m^2",
                       motions[static_cast<int>(r.body_motion[o.body])], shapes[static_cast<int>(r.body_shape[o.body].type)],
                       r.body_mass[o.body], r.body_inertia[o.body].x(), r.body_inertia[o.body].y(),
                       r.body_inertia[o.body].z());
    }
    if (o.kind == ObjectKind::rod) {
      const RodModel& rod = m.rods[o.rod];
      Real length = 0, mass = 0;
      for (Index k = 0; k < rod.segments; ++k) {
        length += rod.segment_length[k];
        mass += m.rigid.body_mass[rod.first_body + k];
      }
      s += fmt::format(" {} segments, length {:.6g} m, mass {:.6g} kg", rod.segments, length, mass);
    }
    if (o.has_particles())
      s += fmt::format(" {} particles, {} surface triangles, {} tetrahedra", o.particle_count(), o.surface.size(), o.tets.size());
    s += "\n";
  }
  for_each_family(m.constraints, [&](const auto& family, int) {
    if (family.size() == 0) return;
    s += fmt::format("  constraints {:<17} {:>8}  in {} colours\n", family.kName, family.size(),
                     family.batches.color_count());
  });
  if (!m.joints.empty()) s += fmt::format("  joints: {}\n", m.joints.size());
  if (!m.fluid.empty())
    s += fmt::format("  fluid: support h = {} m, {} collider wall samples\n", m.fluid.support(), m.fluid.boundary.size());
  s += fmt::format("  probes: {}\n", scene_.probes.size());
  return s;
}

}  // namespace

std::unique_ptr<Engine> make_constraint_engine(Scene& scene) { return std::make_unique<ConstraintEngine>(scene); }

}  // namespace moreau
