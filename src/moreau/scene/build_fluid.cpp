// Fluid objects: particles on a lattice of spacing 2 r filling blocks or a closed mesh, and the
// phase constants; finish_fluids() then samples the collider walls and scales the solver constants.
#include <fmt/format.h>

#include <cmath>
#include <cstdint>

#include "moreau/fluids/boundary_sampling.hpp"
#include "moreau/fluids/density_constraint.hpp"
#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/fluids/fluid_viscosity.hpp"
#include "moreau/fluids/phase_drift.hpp"
#include "moreau/fluids/solid_sampling.hpp"
#include "moreau/fluids/surface_tension.hpp"
#include "moreau/geometry/point_in_mesh.hpp"
#include "moreau/scene/memory_estimate.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

namespace {

// nu dt / h^2 above which "auto" solves the viscosity implicitly (explicit is stable to 0.125).
constexpr Real kStrongViscosity = 0.01;

// Explicit viscosity is stable for dt <= 0.125 h^2 / nu (Monaghan 2005, sec. 6.4).
Real explicit_viscosity_limit(const FluidModel& fm, const FluidPhase& phase) {
  return 0.125 * fm.kernel.h2 / std::max(largest_viscosity(phase), 1e-300);
}

// Lattice points (spacing d) centred in [lo, hi]: floor(L / d) points per axis, each the centre of
// a cube of volume d^3 inside the box, so the particles represent the box volume. `slack`: how far
// (in spacings) the length may fall short of a whole number of spacings and still count it.
void fill_block(const Vec3& lo, const Vec3& hi, Real d, std::vector<Vec3>& out, Real slack = 1e-9) {
  int n[3];
  Vec3 first;
  for (int a = 0; a < 3; ++a) {
    const Real length = hi[a] - lo[a];
    n[a] = static_cast<int>(std::floor(length / d + slack));
    first[a] = lo[a] + 0.5 * (length - n[a] * d) + 0.5 * d;
  }
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) out.push_back(first + d * Vec3(i, j, k));
}

// Checks a block and appends its lattice points.
void add_block(const FluidBlock& block, const SpecPlace& place, Real d, std::vector<Vec3>& out) {
  const Vec3 lo = place.vector("min", block.min), hi = place.vector("max", block.max);
  if ((hi - lo).minCoeff() < d)
    place.fail("max", fmt::format("the block must be at least one particle spacing 2r = {} m wide along every axis", d));
  double count = 1;
  for (int a = 0; a < 3; ++a) count *= std::floor((hi[a] - lo[a]) / d + 1e-9);
  check_memory(place, "max", count, memory_cost::fluid_particle, "particles");
  fill_block(lo, hi, d, out);
}

// "emitter": a disc or rectangle of lattice points releasing a layer of particles each time the
// flow has advanced one spacing d, from start to stop.
FluidEmitter make_emitter(const FluidEmitterSpec& spec, const SpecPlace& e, Real d, Index phase, Real scene_duration) {
  const EmitterOpening opening = place_emitter_opening(spec, e, d, "particle spacing 2r", scene_duration);
  FluidEmitter emitter;
  emitter.phase = phase;
  emitter.center = opening.center;
  emitter.normal = opening.normal;
  emitter.opening = opening.points;
  const Real area = emitter.opening.size() * d * d;  // what the lattice opening carries
  if (spec.mass_rate) e.fail("mass_rate", "a fluid is poured at a \"flow_rate\" (m^3/s) or a \"speed\" (m/s)");
  if (spec.speed.has_value() == spec.flow_rate.has_value())
    e.fail("speed", "give exactly one of \"speed\" (m/s) or \"flow_rate\" (m^3/s)");
  emitter.speed = spec.speed ? e.number("speed", *spec.speed, Range::positive())
                             : e.number("flow_rate", *spec.flow_rate, Range::positive()) / area;
  emitter.start = opening.start;
  emitter.stop = opening.stop;
  emitter.layers = emitter_layers(opening, e, emitter.speed, d);
  emitter.nozzle_length = e.number("nozzle_length", spec.nozzle_length.value_or(2 * d), Range::non_negative());
  return emitter;
}

FluidGasSpec read_gas(const JsonObject& gas) {
  FluidGasSpec spec;
  spec.drag = gas.number("drag", spec.drag);
  spec.wind = read_vector(gas, "wind", spec.wind);
  spec.mixing = gas.number("mixing", spec.mixing);
  gas.finish();
  return spec;
}

FluidThermalSpec read_thermal(const JsonObject& thermal) {
  FluidThermalSpec spec;
  spec.temperature = thermal.number("temperature", spec.temperature);
  spec.conductivity = thermal.number("conductivity", spec.conductivity);
  spec.specific_heat = thermal.number("specific_heat", spec.specific_heat);
  spec.melting_point = read_optional_number(thermal, "melting_point");
  spec.latent_heat = thermal.number("latent_heat", spec.latent_heat);
  spec.solid_viscosity = read_optional_number(thermal, "solid_viscosity");
  spec.expansion = thermal.number("expansion", spec.expansion);
  spec.reference_temperature = read_optional_number(thermal, "reference_temperature");
  thermal.finish();
  return spec;
}

// "thermal": the phase's temperature, conduction and melting (fluid_heat.hpp). Call after the
// phase's viscosity is set (the default of solid_viscosity).
void set_thermal(const FluidThermalSpec& spec, const SpecPlace& t, FluidPhase& phase) {
  phase.temperature = t.number("temperature", spec.temperature, Range::positive());
  phase.conductivity = t.number("conductivity", spec.conductivity, Range::non_negative());
  phase.specific_heat = t.number("specific_heat", spec.specific_heat, Range::positive());
  // Buoyancy: gravity scaled by 1 - beta (T - T_ref) (fluid_heat.hpp). |beta| <= 0.1 1/K covers
  // liquids (water 2.1e-4) and ideal gases down to 10 K (beta = 1 / T).
  phase.expansion = t.number("expansion", spec.expansion, Range::closed(-0.1, 0.1));
  if (phase.expansion != 0) {
    if (!spec.reference_temperature)
      t.fail("reference_temperature", "an \"expansion\" needs the temperature (K) at which the fluid has its "
                                      "\"density\": hotter particles weigh less, colder ones more");
    phase.reference_temperature = t.number("reference_temperature", *spec.reference_temperature, Range::positive());
  } else if (spec.reference_temperature)
    t.fail("reference_temperature", "a reference temperature sets the buoyancy of an \"expansion\" (1/K); give one, "
                                    "or remove the reference temperature");
  if (!spec.melting_point) {
    if (spec.latent_heat != 0) t.fail("latent_heat", "a latent heat needs a \"melting_point\" (K)");
    if (spec.solid_viscosity) t.fail("solid_viscosity", "a solid viscosity needs a \"melting_point\" (K)");
    return;
  }
  phase.melting_point = t.number("melting_point", *spec.melting_point, Range::positive());
  phase.latent_heat = t.number("latent_heat", spec.latent_heat, Range::non_negative());
  phase.solid_viscosity = spec.solid_viscosity
                              ? t.number("solid_viscosity", *spec.solid_viscosity, Range::positive()) / phase.rest_density
                              : phase.viscosity;
}

}  // namespace

FluidSpec read_fluid(const JsonObject& object) {
  FluidSpec spec;
  spec.particle_radius = object.number("particle_radius");
  spec.density = object.number("density", spec.density);
  spec.viscosity = object.number("viscosity", spec.viscosity);
  spec.xsph = object.number("xsph", spec.xsph);
  spec.vorticity = object.number("vorticity", spec.vorticity);
  spec.surface_tension = object.number("surface_tension", spec.surface_tension);
  spec.contact_angle_deg = read_optional_number(object, "contact_angle_deg");
  if (object.has("interfacial_tension")) {
    // {"<other fluid>": sigma, ...}: the names are the scene's, checked when every fluid is known.
    const JsonObject tensions = object.object("interfacial_tension");
    for (const std::string& fluid : tensions.keys()) spec.interfacial_tension.push_back({fluid, tensions.number(fluid)});
  }
  spec.relaxation = object.number("relaxation", spec.relaxation);
  spec.bulk_modulus = object.number("bulk_modulus", spec.bulk_modulus);
  if (object.has("block")) spec.block = read_block(object.object("block"));
  for (const JsonObject& block : object.object_list("blocks")) spec.blocks.push_back(read_block(block));
  // An empty list or path is a source that holds nothing, not the absence of one.
  if (object.has("blocks") && spec.blocks.empty()) object.fail("blocks", "the list holds no block; give at least one");
  if (object.has("mesh")) spec.mesh = object.string("mesh");
  if (object.has("mesh") && spec.mesh.empty()) object.fail("mesh", "give the path of a closed OBJ surface");
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  if (object.has("emitter")) spec.emitter = read_emitter(object.object("emitter"));
  if (object.has("thermal")) spec.thermal = read_thermal(object.object("thermal"));
  if (object.has("gas")) spec.gas = read_gas(object.object("gas"));
  return spec;
}

void add_fluid(const FluidSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& model = ctx.model;
  FluidModel& fm = model.fluid;
  info.kind = ObjectKind::fluid;

  const Real r = place.required("particle_radius", spec.particle_radius, Range::positive());
  if (fm.empty()) {
    fm.particle_radius = r;
    fm.particle_volume = 8 * r * r * r;
    fm.kernel = CubicSplineKernel(4 * r);
  } else if (std::abs(r - fm.particle_radius) > 1e-12 * fm.particle_radius) {
    place.fail("particle_radius", fmt::format("all fluids share one particle radius; an earlier fluid uses {} m",
                                              fm.particle_radius));
  }
  const Real d = 2 * r;

  FluidPhase phase;
  phase.object = static_cast<Index>(model.objects.size());
  phase.rest_density = place.number("density", spec.density, Range::positive());
  phase.particle_mass = phase.rest_density * fm.particle_volume;
  // The scene gives the dynamic viscosity mu (Pa s), as for the FEM engine's fluid; the SPH
  // Laplacian uses the kinematic nu = mu / rho0.
  const Real dynamic_viscosity = place.number("viscosity", spec.viscosity, Range::non_negative());
  phase.viscosity = dynamic_viscosity / phase.rest_density;
  phase.xsph = place.number("xsph", spec.xsph, Range::closed(0, 1));
  phase.vorticity = place.number("vorticity", spec.vorticity, Range::non_negative());
  phase.surface_tension = place.number("surface_tension", spec.surface_tension, Range::non_negative());
  const Real relaxation = place.number("relaxation", spec.relaxation, Range::closed(0, 1e6));
  const Real rest_denominator = fluid_rest_denominator(fm.kernel, d, phase.particle_mass);
  phase.relaxation = relaxation * rest_denominator;
  // Under "nmd" the density row C = V sum W - 1 has the multiplier lambda = -p V (J), so the
  // compliance of a bulk modulus K (C = p / K) is eps = 1 / (K V) (constraint_fluid.hpp).
  phase.compliance = 1 / (place.number("bulk_modulus", spec.bulk_modulus, Range::positive()) * fm.particle_volume);
  if (spec.thermal) {
    set_thermal(*spec.thermal, place.at("thermal"), phase);
    fm.thermal = true;
    fm.buoyant = fm.buoyant || phase.expansion != 0;
  }
  if (spec.gas) {  // a gas in open air (ambient_air.hpp)
    const SpecPlace g = place.at("gas");
    phase.gas = true;
    phase.gas_drag = g.number("drag", spec.gas->drag, Range::non_negative());
    phase.wind = g.vector("wind", spec.gas->wind);
    phase.gas_mixing = g.number("mixing", spec.gas->mixing, Range::non_negative());
    fm.gas = fm.buoyant = true;
  }
  // A liquid's Boussinesq weight m g (1 - beta (T - T_ref)) holds for small beta (T - T_ref); a gas
  // in open air's -beta (T - T_ref) g is exact for an ideal gas (ambient_air.hpp).
  if (const Real change = phase.expansion * (phase.temperature - phase.reference_temperature);
      !phase.gas && std::abs(change) > 0.5)
    place.at("thermal").fail("expansion", fmt::format("expansion x (temperature - reference_temperature) = {:.3g}: the "
                                                      "Boussinesq weight m g (1 - beta (T - T_ref)) would change by more "
                                                      "than half; allowed: at most 0.5 in size (a \"gas\" in open air "
                                                      "has no such limit)",
                                                      change));

  if (fm.viscosity_solver == ViscositySolver::explicit_update && model.settings.dt > explicit_viscosity_limit(fm, phase))
    place.fail("viscosity", fmt::format("explicit viscosity (settings.fluid.viscosity_solver) needs dt <= 0.125 h^2 / nu = "
                                        "{:.3g} s with h = 4 r = {} m and nu = mu / rho0 = {:.3g} m^2/s; settings.dt is {} s: "
                                        "use the implicit solver (\"auto\" or \"implicit\"), or lower the viscosity or dt",
                                        explicit_viscosity_limit(fm, phase), fm.kernel.h, largest_viscosity(phase),
                                        model.settings.dt));

  if (spec.contact_angle_deg) {
    if (spec.gas) place.fail("contact_angle_deg", "a gas does not wet the walls; give the contact angle to a liquid");
    if (phase.surface_tension == 0)
      place.fail("contact_angle_deg", "a contact angle is a balance of surface tensions: give the fluid a "
                                      "\"surface_tension\" (N/m) too");
    // Young-Dupre's work of adhesion (wall_adhesion.hpp).
    const Real theta = place.number("contact_angle_deg", *spec.contact_angle_deg, Range::closed(0, 180)) * kPi / 180;
    phase.wall_adhesion = phase.surface_tension * (1 + std::cos(theta));
  }
  if (phase.surface_tension > 0) {
    const Real limit = capillary_time_step(phase.rest_density, d, phase.surface_tension);
    if (model.settings.dt > limit)
      place.fail("surface_tension",
                 fmt::format("surface tension {} N/m needs dt <= sqrt(rho0 (2r)^3 / (2 pi gamma)) = {:.3g} s to resolve "
                             "the capillary waves on the particle spacing 2r = {} m; settings.dt is {} s: lower dt or "
                             "the surface tension, or use larger particles",
                             phase.surface_tension, limit, d, model.settings.dt));
  }

  std::vector<Vec3> points;
  const int sources = spec.block.has_value() + !spec.blocks.empty() + !spec.mesh.empty();
  const bool emits = spec.emitter.has_value();
  if (sources > 1 || (sources == 0 && !emits))
    place.fail("block", "give exactly one of \"block\", \"blocks\" or \"mesh\" for the fluid's initial volume, "
                        "or an \"emitter\" (or both)");
  if (spec.block) add_block(*spec.block, place.at("block"), d, points);
  for (size_t k = 0; k < spec.blocks.size(); ++k) add_block(spec.blocks[k], place.at(fmt::format("blocks[{}]", k)), d, points);
  if (!spec.mesh.empty()) {
    // Lattice points inside a closed OBJ surface.
    const ClosedSurface surface = read_closed_surface(ctx, place, "mesh", spec.mesh);
    // The OBJ reader (tinyobjloader) stores vertices in single precision, relative error 6e-8: a
    // bounding box a whole number of spacings wide may come out a few 1e-7 spacings short, so the
    // count allows 1e-5 of a spacing (blocks, read in double precision, allow 1e-9).
    std::vector<Vec3> lattice;
    fill_block(surface.lo, surface.hi, d, lattice, 1e-5);
    for (const Vec3& p : lattice)
      if (point_in_closed_mesh(surface.mesh, p)) points.push_back(p);
  }
  if (points.empty() && sources > 0) place.fail(spec.mesh.empty() ? "block" : "mesh", "the fluid volume holds no particle of spacing 2r");

  const Vec3 velocity = place.vector("velocity", spec.velocity);
  info.fluid_phase = static_cast<Index>(fm.phases.size());
  if (emits) fm.emitters.push_back(make_emitter(*spec.emitter, place.at("emitter"), d, info.fluid_phase, ctx.duration));
  // Particle indices are 32-bit: the scene's initial plus emitted particles, summed in 64 bits.
  std::int64_t total = static_cast<std::int64_t>(fm.initial_position.size()) + static_cast<std::int64_t>(points.size());
  for (const FluidEmitter& e : fm.emitters) total += e.capacity();
  constexpr std::int64_t kMaxFluidParticles = 1'000'000'000;
  if (total > kMaxFluidParticles)
    place.fail(emits ? "emitter" : "particle_radius",
               fmt::format("the scene's fluids would hold {} particles (initial plus emitted); the limit is {}", total,
                           kMaxFluidParticles));
  for (const Vec3& p : points) {
    fm.initial_position.push_back(p);
    fm.initial_velocity.push_back(velocity);
    fm.initial_phase.push_back(info.fluid_phase);
  }
  fm.phases.push_back(phase);
}

namespace {

// Every fluid particle is kept inside every container (a collider with "inside": true), so a
// particle that starts outside one would be thrown into it, and two containers apart from each
// other would leave it no place at all. Refuses a container with a fluid particle (or an emitter's
// opening) outside it, naming the fluid.
void check_fluid_inside_containers(const Model& model, const std::function<SpecPlace(Index object)>& object_place) {
  const FluidModel& fm = model.fluid;
  auto fluid_name = [&](Index phase) -> std::string {
    for (const ObjectInfo& object : model.objects)
      if (object.kind == ObjectKind::fluid && object.fluid_phase == phase) return object.name;
    return "?";
  };
  for (std::size_t k = 0; k < model.objects.size(); ++k) {
    const ObjectInfo& container = model.objects[k];
    if (container.kind != ObjectKind::collider || !model.colliders[container.collider].inside) continue;
    const Collider& c = model.colliders[container.collider];
    auto outside = [&](const Vec3& x) { return collider_distance(c, c.position_at(0), x).distance < 0; };
    auto refuse = [&](Index phase, const Vec3& x) {
      object_place(static_cast<Index>(k))
          .fail("shape", fmt::format("the fluid '{}' starts outside this container (\"inside\": true) at "
                                     "[{:.4g}, {:.4g}, {:.4g}] m; fluid particles are kept inside every container, "
                                     "so every fluid must start inside all of them (two containers apart from each "
                                     "other cannot both hold it)",
                                     fluid_name(phase), x.x(), x.y(), x.z()));
    };
    for (std::size_t i = 0; i < fm.initial_position.size(); ++i)
      if (outside(fm.initial_position[i])) refuse(fm.initial_phase[i], fm.initial_position[i]);
    for (const FluidEmitter& e : fm.emitters)
      if (outside(e.center)) refuse(e.phase, e.center);
  }
}

}  // namespace

void finish_fluids(Model& model, const std::function<SpecPlace(Index object)>& object_place) {
  FluidModel& fm = model.fluid;
  // A heated or cooled wall warms only fluids that carry heat.
  for (std::size_t k = 0; k < model.objects.size(); ++k) {
    const ObjectInfo& object = model.objects[k];
    if (!fm.thermal && object.kind == ObjectKind::collider && model.colliders[object.collider].temperature)
      object_place(static_cast<Index>(k))
          .fail("temperature", "no fluid of the scene carries heat: give the fluids a \"thermal\" entry, or remove "
                               "the wall's \"temperature\"");
  }
  // A solid's fluid friction grips the particle fluids through their viscosity: without a viscous
  // fluid it would do nothing.
  for (std::size_t k = 0; k < model.objects.size(); ++k)
    if (model.objects[k].fluid_friction > 0 && !fluid_has_viscosity(model))
      object_place(static_cast<Index>(k))
          .fail("fluid_friction", fm.empty() ? "the scene has no particle fluid for the surface to grip; remove "
                                               "\"fluid_friction\""
                                             : "the surface grips the particle fluids through their viscosity, and no "
                                               "fluid of the scene has one; give a fluid a \"viscosity\" or remove "
                                               "\"fluid_friction\"");
  if (fm.empty()) return;
  fm.heat_step_limit = fluid_heat_step_limit(fm);
  const Real d = 2 * fm.particle_radius;
  fm.tensile_inv_w_dq = 1 / fm.kernel.value(0.2 * fm.kernel.h);
  constexpr Real kReferenceGravity = 9.81;  // m/s^2 (density_constraint.hpp: s_corr)
  fm.tensile_reference = kReferenceGravity * fm.kernel.h;
  fm.neighbor_skin = fm.neighbor_skin_fraction * fm.kernel.h;
  fm.solid_contact_distance = 1.5 * fm.particle_radius;  // solid_coupling.hpp
  if (fm.phase_drift) set_up_phase_drift(fm, model.settings.gravity.norm());
  // "auto": the implicit, accurate viscosity where it acts strongly within a step or walls have
  // fluid friction; the fast explicit one otherwise (water at any practical particle size).
  bool wall_friction = false;
  for (const Collider& c : model.colliders) wall_friction |= c.fluid_walls && c.fluid_friction > 0;
  for (const ObjectInfo& object : model.objects) wall_friction |= object.fluid_friction > 0;
  if (fm.viscosity_solver == ViscositySolver::automatic) {
    bool strong = false;
    for (const FluidPhase& phase : fm.phases)
      strong |= largest_viscosity(phase) * model.settings.dt > kStrongViscosity * fm.kernel.h2;
    fm.viscosity_solver = strong || wall_friction ? ViscositySolver::implicit_solve : ViscositySolver::explicit_update;
  }
  if (wall_friction && fm.viscosity_solver == ViscositySolver::explicit_update) {
    for (std::size_t k = 0; k < model.objects.size(); ++k) {
      const ObjectInfo& object = model.objects[k];
      if ((object.kind == ObjectKind::collider && model.colliders[object.collider].fluid_friction > 0) ||
          object.fluid_friction > 0)
        object_place(static_cast<Index>(k))
            .fail("fluid_friction", "the fluid's wall friction is part of the implicit viscosity: set "
                                    "settings.fluid.viscosity_solver to \"implicit\" or \"auto\"");
    }
  }
  check_fluid_inside_containers(model, object_place);
  fm.capacity = fm.initial_count();  // build_fluid checked that the total fits
  for (const FluidEmitter& e : fm.emitters) fm.capacity += e.capacity();

  // Planes are sampled on a patch around the fluid, a few fluid extents wide.
  std::vector<Vec3> fluid_points = fm.initial_position;
  for (const FluidEmitter& e : fm.emitters) fluid_points.push_back(e.center);
  Vec3 lo = fluid_points.front(), hi = lo;
  for (const Vec3& p : fluid_points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (const Vec3& p : model.particle_rest_position) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Real plane_half_size = std::max(1.0, 1.5 * (hi - lo).maxCoeff());
  std::vector<Index> sampled;
  for (Index c = 0; c < static_cast<Index>(model.colliders.size()); ++c)
    if (model.colliders[c].fluid_walls) sampled.push_back(c);
  // A collider's samples are counted before any is made: a tank kilometres wide is refused here.
  for (std::size_t k = 0; k < model.objects.size(); ++k)
    if (model.objects[k].kind == ObjectKind::collider && model.colliders[model.objects[k].collider].fluid_walls)
      check_memory(object_place(static_cast<Index>(k)), "shape",
                   collider_surface_sample_count(model.colliders[model.objects[k].collider], d, 0.5 * d, plane_half_size),
                   memory_cost::fluid_wall_sample, "fluid wall samples at the fluid's particle spacing");
  fm.boundary = sample_fluid_walls(model.colliders, sampled, d, fm.kernel, 0.5 * (lo + hi), plane_half_size);
  fm.solid = sample_fluid_solids(model, fm.particle_radius, fm.kernel);
}

}  // namespace moreau
