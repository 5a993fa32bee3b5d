// "settings" of a constraint-engine scene: read from JSON, then checked and applied to the scene.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "moreau/scene/spec_builders.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/solvers/solver_registry.hpp"

namespace moreau {

void read_output_settings(const JsonObject& settings, int& every, FrameFormats& formats, int& checkpoint_every,
                          bool surfaces_and_points) {
  if (auto output = settings.optional_object("output")) {
    every = output->integer("every", every, 1);
    checkpoint_every = output->integer("checkpoint_every", checkpoint_every, 0);
    if (output->has("formats")) {
      const char* allowed = surfaces_and_points ? "vtk, obj, ply" : "vtk (FEM scenes)";
      const auto& names = output->raw("formats");
      if (!names.is_array()) output->fail("formats", fmt::format("expected an array of format names; allowed: {}", allowed));
      formats = {.vtk = false};
      for (const auto& f : names) {
        const std::string name = f.is_string() ? f.get<std::string>() : "";
        bool* format = name == "vtk" ? &formats.vtk : !surfaces_and_points ? nullptr
                     : name == "obj" ? &formats.obj : name == "ply" ? &formats.ply : nullptr;
        if (!format) output->fail("formats", fmt::format("{} is not a known format; allowed: {}", f.dump(), allowed));
        *format = true;
      }
    }
    output->finish();
  }
}

SceneSettings read_settings(const JsonObject& settings) {
  SceneSettings s;
  if (settings.has("solver")) s.solver = settings.string("solver");
  s.dt = read_optional_number(settings, "dt");
  s.duration = read_optional_number(settings, "duration");
  s.gravity = read_optional_vector(settings, "gravity");
  if (settings.has("threads")) s.threads = read_integer(settings, "threads");
  if (settings.has("substeps")) s.substeps = read_integer(settings, "substeps");
  if (settings.has("iterations")) s.iterations = read_integer(settings, "iterations");
  if (settings.has("particle_contacts")) s.particle_contacts = settings.boolean("particle_contacts", true);
  s.max_speed = read_optional_number(settings, "max_speed");
  if (settings.has("joint_solver")) s.joint_solver = settings.string("joint_solver");
  if (auto fluid = settings.optional_object("fluid")) {
    s.fluid.neighbor_skin = read_optional_number(*fluid, "neighbor_skin");
    s.fluid.tensile_k = read_optional_number(*fluid, "tensile_k");
    s.fluid.cfl_limit = read_optional_number(*fluid, "cfl_limit");
    if (fluid->has("viscosity_solver")) s.fluid.viscosity_solver = fluid->string("viscosity_solver");
    s.fluid.viscosity_tolerance = read_optional_number(*fluid, "viscosity_tolerance");
    if (fluid->has("viscosity_iterations")) s.fluid.viscosity_iterations = read_integer(*fluid, "viscosity_iterations");
    if (fluid->has("phase_drift")) s.fluid.phase_drift = fluid->boolean("phase_drift", false);
    fluid->finish();
  }
  if (auto nmd = settings.optional_object("nmd")) {
    if (nmd->has("method")) s.nmd.method = nmd->string("method");
    s.nmd.tolerance = read_optional_number(*nmd, "tolerance");
    if (nmd->has("substeps")) s.nmd.substeps = read_integer(*nmd, "substeps");
    if (nmd->has("iterations")) s.nmd.iterations = read_integer(*nmd, "iterations");
    s.nmd.over_relaxation = read_optional_number(*nmd, "over_relaxation");
    s.nmd.stabilization = read_optional_number(*nmd, "stabilization");
    if (nmd->has("friction")) s.nmd.friction = nmd->string("friction");
    s.nmd.restitution_threshold = read_optional_number(*nmd, "restitution_threshold");
    s.nmd.sliding_speed = read_optional_number(*nmd, "sliding_speed");
    s.nmd.contact_compliance = read_optional_number(*nmd, "contact_compliance");
    if (nmd->has("warm_start")) s.nmd.warm_start = nmd->boolean("warm_start", true);
    nmd->finish();
  }
  if (auto xpbi = settings.optional_object("xpbi")) {
    s.xpbi.xsph = read_optional_number(*xpbi, "xsph");
    s.xpbi.min_distance = read_optional_number(*xpbi, "min_distance");
    if (xpbi->has("packing_volume")) s.xpbi.packing_volume = xpbi->boolean("packing_volume", true);
    xpbi->finish();
  }
  if (auto sleep = settings.optional_object("sleep")) {
    s.sleep = SleepSolverSettings{read_optional_number(*sleep, "speed"), read_optional_number(*sleep, "time")};
    sleep->finish();
  }
  FrameFormats formats{.vtk = s.write_vtk, .obj = s.write_obj, .ply = s.write_ply};
  read_output_settings(settings, s.output_every, formats, s.checkpoint_every, true);
  s.write_vtk = formats.vtk;
  s.write_obj = formats.obj;
  s.write_ply = formats.ply;
  settings.finish();
  return s;
}

void apply_settings(const SceneSettings& spec, const SpecPlace& place, Scene& scene) {
  // The scene format names every formulation; those not registered (solver_registry.hpp) are
  // refused with the list of the ones that are.
  std::vector<std::string> available = registered_solver_names();
  available.push_back("fem");
  place.choice("solver", spec.solver, {"xpbd", "nmd", "xpbi", "fem"});
  if (std::find(available.begin(), available.end(), spec.solver) == available.end())
    place.fail("solver", fmt::format("the '{}' formulation is not available in this version of moreau; allowed: {}",
                                     spec.solver, fmt::join(available, ", ")));
  if (spec.solver == "fem") place.fail("solver", "FEM scenes are read from scene JSON (World::load or World::from_json)");
  scene.solver = spec.solver;
  SolverSettings& s = scene.model.settings;
  s.dt = place.number("dt", spec.dt.value_or(s.dt), Range::positive());
  scene.duration = place.number("duration", spec.duration.value_or(scene.duration), Range::positive());
  if (spec.gravity) s.gravity = place.vector("gravity", *spec.gravity);
  s.threads = place.integer("threads", spec.threads.value_or(s.threads), 0, 1024);
  s.substeps = place.integer("substeps", spec.substeps.value_or(s.substeps), 1, 100000);
  s.iterations = place.integer("iterations", spec.iterations.value_or(s.iterations), 1, 100000);
  s.particle_contacts = spec.particle_contacts.value_or(s.particle_contacts);
  s.max_speed = place.number("max_speed", spec.max_speed.value_or(s.max_speed), Range::positive());
  s.joint_solver = place.choice("joint_solver", spec.joint_solver, {"direct", "gauss_seidel"}) == "direct"
                       ? JointSolver::direct
                       : JointSolver::gauss_seidel;
  FluidModel& fm = scene.model.fluid;
  const SpecPlace fluid = place.at("fluid");
  fm.neighbor_skin_fraction = fluid.number("neighbor_skin", spec.fluid.neighbor_skin.value_or(fm.neighbor_skin_fraction), Range::closed(0, 1));
  fm.tensile_k = fluid.number("tensile_k", spec.fluid.tensile_k.value_or(fm.tensile_k), Range::closed(0, 10));
  fm.cfl_limit = fluid.number("cfl_limit", spec.fluid.cfl_limit.value_or(fm.cfl_limit), Range::positive());
  const std::string viscosity_solver =
      fluid.choice("viscosity_solver", spec.fluid.viscosity_solver, {"auto", "explicit", "implicit"});
  fm.viscosity_solver = viscosity_solver == "auto"       ? ViscositySolver::automatic
                        : viscosity_solver == "explicit" ? ViscositySolver::explicit_update
                                                         : ViscositySolver::implicit_solve;
  fm.viscosity_tolerance = fluid.number("viscosity_tolerance", spec.fluid.viscosity_tolerance.value_or(fm.viscosity_tolerance),
                                        Range::open(0, 1));
  fm.viscosity_max_iterations = fluid.integer(
      "viscosity_iterations", spec.fluid.viscosity_iterations.value_or(fm.viscosity_max_iterations), 1, 100000);
  fm.phase_drift = spec.fluid.phase_drift.value_or(fm.phase_drift);
  NmdSettings& nmd = s.nmd;
  const NmdSolverSettings& ns = spec.nmd;
  const SpecPlace nmd_place = place.at("nmd");
  const std::string method = nmd_place.choice("method", ns.method, {"pgs", "direct", "hybrid"});
  nmd.method = method == "pgs" ? NmdMethod::pgs : method == "direct" ? NmdMethod::direct : NmdMethod::hybrid;
  nmd.tolerance = nmd_place.number("tolerance", ns.tolerance.value_or(nmd.tolerance), Range::non_negative());
  nmd.substeps = nmd_place.integer("substeps", ns.substeps.value_or(nmd.substeps), 1, 100000);
  nmd.iterations = nmd_place.integer("iterations", ns.iterations.value_or(nmd.iterations), 1, 100000);
  nmd.over_relaxation =
      nmd_place.number("over_relaxation", ns.over_relaxation.value_or(nmd.over_relaxation), Range::open(0, 2));
  nmd.stabilization = nmd_place.number("stabilization", ns.stabilization.value_or(nmd.stabilization), Range::non_negative());
  nmd.friction = nmd_place.choice("friction", ns.friction, {"cone", "box"}) == "cone" ? FrictionBound::cone
                                                                                       : FrictionBound::box;
  nmd.restitution_threshold = nmd_place.number(
      "restitution_threshold", ns.restitution_threshold.value_or(nmd.restitution_threshold), Range::non_negative());
  nmd.sliding_speed = nmd_place.number("sliding_speed", ns.sliding_speed.value_or(nmd.sliding_speed), Range::non_negative());
  nmd.contact_compliance =
      nmd_place.number("contact_compliance", ns.contact_compliance.value_or(nmd.contact_compliance), Range::non_negative());
  nmd.warm_start = ns.warm_start.value_or(nmd.warm_start);
  const SpecPlace xpbi = place.at("xpbi");
  s.xpbi.xsph = xpbi.number("xsph", spec.xpbi.xsph.value_or(s.xpbi.xsph), Range::closed(0, 1));
  s.xpbi.min_distance =
      xpbi.number("min_distance", spec.xpbi.min_distance.value_or(s.xpbi.min_distance), Range::closed(0, 1));
  s.xpbi.packing_volume = spec.xpbi.packing_volume.value_or(s.xpbi.packing_volume);
  if (spec.sleep) {
    const SpecPlace sleep = place.at("sleep");
    s.sleep.enabled = true;
    s.sleep.speed = sleep.number("speed", spec.sleep->speed.value_or(s.sleep.speed), Range::positive());
    s.sleep.time = sleep.number("time", spec.sleep->time.value_or(s.sleep.time), Range::positive());
  }
  scene.output.every = place.integer("output.every", spec.output_every, 1);
  scene.output.formats = {.vtk = spec.write_vtk, .obj = spec.write_obj, .ply = spec.write_ply};
  scene.output.checkpoint_every = place.integer("output.checkpoint_every", spec.checkpoint_every, 0);
}

}  // namespace moreau
