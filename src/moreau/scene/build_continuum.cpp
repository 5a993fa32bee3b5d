// "kind": "continuum" objects: particles on a cubic lattice of spacing r (one per cell, at its
// centre) filling boxes, cylinders, spheres or a closed mesh, or poured by an emitter, each
// carrying the mass and rest volume r^3 of its cell, a deformation gradient and its material's
// elastic law and plastic flow (continuum/continuum_model.hpp). Simulated by XPBI (solvers/xpbi/).
#include <fmt/format.h>

#include "moreau/geometry/cell_grid.hpp"
#include "moreau/scene/filled_regions.hpp"

namespace moreau {

namespace {

constexpr Index kMaxContinuumParticles = 20'000'000;

// The lattice points in the z-order (Morton order) of their cells: a particle's neighbours are then
// close to it in memory, and XPBI's sweeps, which visit the particles block by block and read some
// 30 neighbours of each, find them in cache (the lattice's own row order puts the neighbours of
// the next layer a whole layer away).
std::vector<Vec3> in_z_order(const std::vector<Vec3>& points, Real spacing) {
  Vec3 lo = points.front();
  for (const Vec3& x : points) lo = lo.cwiseMin(x);
  CellGrid grid;
  grid.build(points.data(), static_cast<Index>(points.size()), GridFrame{lo - Vec3::Constant(spacing / 2), spacing});
  std::vector<Vec3> sorted;
  sorted.reserve(points.size());
  for (Index k : grid.order()) sorted.push_back(points[k]);
  return sorted;
}

ContinuumPlasticity read_plasticity(const JsonObject& object) {
  ContinuumPlasticity p;
  p.model = object.choice("model", {"drucker_prager", "von_mises", "snow", "herschel_bulkley", "maxwell"});
  if (p.model == "drucker_prager") {
    p.friction_angle_deg = object.number("friction_angle_deg");
    p.cohesion = object.number("cohesion", p.cohesion);
  } else if (p.model == "von_mises") {
    p.yield_stress = object.number("yield_stress");
  } else if (p.model == "herschel_bulkley") {
    p.shear_yield_stress = object.number("shear_yield_stress");
    p.consistency = object.number("consistency");
    p.flow_index = object.number("flow_index", p.flow_index);
  } else if (p.model == "maxwell") {
    p.relaxation_time = object.number("relaxation_time");
  } else {
    p.critical_compression = object.number("critical_compression", p.critical_compression);
    p.critical_stretch = object.number("critical_stretch", p.critical_stretch);
    p.hardening = object.number("hardening", p.hardening);
  }
  object.finish();
  return p;
}

ContinuumMaterial continuum_material(const ContinuumSpec& spec, const SpecPlace& place) {
  ContinuumMaterial m;
  m.density = place.number("density", spec.density, Range::positive());
  if (!spec.youngs_modulus) place.fail("youngs_modulus", "a continuum needs its Young's modulus E (Pa)");
  m.lame = lame_from_youngs(place.number("youngs_modulus", *spec.youngs_modulus, Range::positive()),
                            place.number("poisson_ratio", spec.poisson_ratio, Range::open(-1, 0.5)));
  if (!spec.plasticity) return m;
  const ContinuumPlasticity& p = *spec.plasticity;
  const SpecPlace at = place.at("plasticity");
  if (p.model == "drucker_prager") {
    m.plastic = PlasticModel::drucker_prager;
    m.friction_angle = at.number("friction_angle_deg", *p.friction_angle_deg, Range::open(0, 90)) * kPi / 180;
    m.cohesion = at.number("cohesion", p.cohesion, Range::non_negative());
  } else if (p.model == "von_mises") {
    m.plastic = PlasticModel::von_mises;
    m.yield_stress = at.number("yield_stress", *p.yield_stress, Range::positive());
  } else if (p.model == "herschel_bulkley") {
    m.plastic = PlasticModel::herschel_bulkley;
    m.shear_yield_stress = at.number("shear_yield_stress", *p.shear_yield_stress, Range::non_negative());
    m.consistency = at.number("consistency", *p.consistency, Range::non_negative());
    m.flow_index = at.number("flow_index", p.flow_index, Range::positive());
  } else if (p.model == "maxwell") {
    m.plastic = PlasticModel::maxwell;
    if (!p.relaxation_time) at.fail("relaxation_time", "a maxwell fluid needs its relaxation time (s)");
    m.relaxation_time = at.number("relaxation_time", *p.relaxation_time, Range::positive());
  } else {
    m.plastic = PlasticModel::snow;
    m.critical_compression = at.number("critical_compression", p.critical_compression, Range::open(0, 1));
    m.critical_stretch = at.number("critical_stretch", p.critical_stretch, Range::positive());
    m.hardening = at.number("hardening", p.hardening, Range::non_negative());
  }
  return m;
}

// The centres of the lattice cells of edge r in the box [lo, hi] that `keep` accepts.
template <class Keep>
void fill_lattice(const SpecPlace& place, const std::string& field, const Vec3& lo, const Vec3& hi, Real r, Keep keep,
                  std::vector<Vec3>& points) {
  const Eigen::Array3d count = ((hi - lo).array() / r + 1e-9).floor();
  if (count.prod() + static_cast<double>(points.size()) > kMaxContinuumParticles)
    place.fail(field, fmt::format("it holds {:.3g} particles of spacing {} m; at most {} per object", count.prod(), r,
                                  kMaxContinuumParticles));
  for (int i = 0; i < count.x(); ++i)
    for (int j = 0; j < count.y(); ++j)
      for (int k = 0; k < count.z(); ++k) {
        const Vec3 x = lo + r * (Vec3(i, j, k) + Vec3::Constant(0.5));
        if (keep(x)) points.push_back(x);
      }
}

// "emitter": the particles of every layer it will release, on the opening's lattice of spacing r,
// appended (after the filled particles) layer after layer (model/particle_emitter.hpp). The rate
// is a speed v, a flow rate Q = N r^2 v (m^3/s) or a mass rate rho N r^2 v (kg/s) for an opening
// of N lattice points.
ParticleEmitter pour_continuum(const EmitterSpec& spec, const SpecPlace& e, Real r, Real density, Real scene_duration,
                               Index filled, std::vector<Vec3>& points) {
  const EmitterOpening opening = place_emitter_opening(spec, e, r, "particle spacing", scene_duration);
  // A layer waits while a particle lies within r/2 + 0.4 r of its plane: 10 % short of the
  // spacing, so the layer released before it, one spacing on, never holds it back by round-off.
  ParticleEmitter emitter = particle_emitter_at(opening, r, 0.4 * r);
  const int rates = spec.speed.has_value() + spec.flow_rate.has_value() + spec.mass_rate.has_value();
  if (rates != 1)
    e.fail("speed", "give exactly one of \"speed\" (m/s), \"flow_rate\" (m^3/s) or \"mass_rate\" (kg/s)");
  const Real area = emitter.per_layer * r * r;  // what the lattice opening carries
  if (spec.speed) emitter.speed = e.number("speed", *spec.speed, Range::positive());
  if (spec.flow_rate) emitter.speed = e.number("flow_rate", *spec.flow_rate, Range::positive()) / area;
  if (spec.mass_rate) emitter.speed = e.number("mass_rate", *spec.mass_rate, Range::positive()) / (density * area);
  emitter.nozzle_length = e.number("nozzle_length", spec.nozzle_length.value_or(2 * r), Range::non_negative());
  if (emitter.nozzle_length > 0 && emitter.nozzle_length < 0.5 * r)
    e.fail("nozzle_length", fmt::format("a nozzle holds at least half a layer: 0 (none) or at least r/2 = {} m", 0.5 * r));
  emitter.layers = emitter_layers(opening, e, emitter.speed, r);
  if (static_cast<double>(filled) + static_cast<double>(emitter.layers) * emitter.per_layer > kMaxContinuumParticles)
    e.fail("stop", fmt::format("the continuum would hold {:.3g} particles with the emitted ones; at most {} per object",
                               static_cast<double>(filled) + static_cast<double>(emitter.layers) * emitter.per_layer,
                               kMaxContinuumParticles));
  for (Index k = 0; k < emitter.layers; ++k)
    for (const Vec3& point : opening.points) points.push_back(opening.center + point);
  return emitter;
}

}  // namespace

ContinuumSpec read_continuum(const JsonObject& object) {
  ContinuumSpec spec;
  spec.regions = read_filled_regions(object);
  if (object.has("emitter")) spec.emitter = read_emitter(object.object("emitter"));
  spec.spacing = object.number("spacing");
  spec.density = object.number("density", spec.density);
  spec.youngs_modulus = read_optional_number(object, "youngs_modulus");
  spec.poisson_ratio = object.number("poisson_ratio", spec.poisson_ratio);
  if (auto plasticity = object.optional_object("plasticity")) spec.plasticity = read_plasticity(*plasticity);
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  spec.contact = read_contact_material(object);
  spec.fluid_coupling = object.boolean("fluid_coupling", spec.fluid_coupling);
  spec.fluid_friction = object.number("fluid_friction", spec.fluid_friction);
  return spec;
}

void add_continuum(const ContinuumSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  const Real r = place.number("spacing", spec.spacing, Range::positive());
  if (m.continuum.spacing > 0 && r != m.continuum.spacing)
    place.fail("spacing", fmt::format("every continuum of a scene shares one particle spacing (their particles are each "
                                      "other's neighbours); an earlier one has {} m",
                                      m.continuum.spacing));
  const ContinuumMaterial material = continuum_material(spec, place);
  if (spec.regions.empty() && !spec.emitter)
    place.fail("blocks", "a continuum needs a block {\"min\", \"max\"}, a cylinder {\"base\", \"radius\", \"height\"}, a "
                         "sphere {\"center\", \"radius\"} or a closed \"mesh\" to fill, or an \"emitter\" to pour it");

  std::vector<Vec3> points;
  fill_regions(spec.regions, place, ctx, {r, 0, "particle spacing"},
               [&](const SpecPlace& at, const std::string& field, const Vec3& lo, const Vec3& hi, auto keep) {
                 fill_lattice(at, field, lo, hi, r, keep, points);
               },
               [&] { return points.size(); });
  if (!points.empty()) points = in_z_order(points, r);
  const Index filled = static_cast<Index>(points.size());
  ParticleEmitter emitter;
  if (spec.emitter)
    emitter = pour_continuum(*spec.emitter, place.at("emitter"), r, material.density, ctx.duration, filled, points);
  if (points.size() < 2) place.fail("blocks", "a continuum needs at least two particles");

  set_contact_material(spec.contact, place, info);
  info.kind = ObjectKind::continuum;
  info.self_collision = false;  // the continuum's constraints hold its particles apart
  set_fluid_coupling(spec.fluid_coupling, spec.fluid_friction, place, info);
  const Real volume = r * r * r;
  add_particles(ctx, info, points, std::vector<Real>(points.size(), material.density * volume), r / 2, r / 2,
                place.vector("velocity", spec.velocity));
  ContinuumModel& continuum = m.continuum;
  continuum.spacing = r;
  const Index material_index = static_cast<Index>(continuum.materials.size());
  continuum.materials.push_back(material);
  for (Index p = info.particle_begin; p < info.particle_end; ++p) {
    m.contact_particle.push_back(p);
    continuum.particle.push_back(p);
    continuum.rest_volume.push_back(volume);
    continuum.material.push_back(material_index);
  }
  if (spec.emitter) {
    emitter.object = static_cast<Index>(m.objects.size());  // the object being added
    emitter.first = info.particle_begin + filled;
    for (Index p = emitter.first; p < info.particle_end; ++p) ctx.initial_velocity[p] = Vec3::Zero();  // set when released
    m.particle_emitters.push_back(emitter);
  }
}

}  // namespace moreau
