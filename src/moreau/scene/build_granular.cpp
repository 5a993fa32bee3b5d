// "kind": "granular" objects: grains as particles on a lattice filling boxes, cylinders, spheres or
// a closed mesh, or poured by an emitter, each touching the others, colliders, rigid bodies and
// rods through the particle contacts (with friction, restitution and cohesion); polydisperse radii
// drawn from a seeded generator.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "moreau/scene/filled_regions.hpp"

namespace moreau {

namespace {

// A uniform number in [0, 1) from the generator's raw 64 bits (the same on every platform,
// unlike the standard distributions).
Real unit_draw(std::mt19937_64& generator) { return static_cast<Real>(generator() >> 11) * 0x1.0p-53; }

constexpr Index kMaxGrains = 50'000'000;

// The centres of a clump's spheres about its centre, in units of their radius r, for spheres s r
// apart: a pair along x, an equilateral triangle in the xy plane, a regular tetrahedron.
std::vector<Vec3> clump_offsets(int spheres, Real s) {
  switch (spheres) {
    case 2: return {Vec3(-s / 2, 0, 0), Vec3(s / 2, 0, 0)};
    case 3: {
      const Real R = s / std::sqrt(3.0);  // circumradius of the triangle of side s
      return {R * Vec3(1, 0, 0), R * Vec3(-0.5, std::sqrt(0.75), 0), R * Vec3(-0.5, -std::sqrt(0.75), 0)};
    }
    default: {
      const Real a = s / (2 * std::sqrt(2.0));  // the corners (+-a, +-a, +-a) with an even number of minus signs
      return {Vec3(a, a, a), Vec3(a, -a, -a), Vec3(-a, a, -a), Vec3(-a, -a, a)};
    }
  }
}

// A rotation drawn uniformly from three draws (Shoemake 1992, "Uniform random rotations").
Mat3 uniform_rotation(Real u1, Real u2, Real u3) {
  const Real a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return Quat(b * std::cos(2 * kPi * u3), a * std::sin(2 * kPi * u2), a * std::cos(2 * kPi * u2), b * std::sin(2 * kPi * u3))
      .normalized()
      .toRotationMatrix();
}

// Grains on a cubic lattice of spacing 2 R_max (1 + 2 %), each moved by up to 1 % of r_max in
// each direction so that no column stands balanced on an exact stack; grains never overlap at
// rest. R_max is r_max for spheres, and a clump's bounding radius (r_max plus its farthest
// sphere centre) for clumps, each turned by a drawn rotation. Fills the box [lo, hi] where `keep`
// accepts a lattice point (before its move).
class GrainLattice {
 public:
  GrainLattice(Real r_min, Real r_max, Real density, std::uint64_t seed, std::vector<Vec3> clump = {})
      : r_min_(r_min), r_max_(r_max), density_(density), generator_(seed), clump_(std::move(clump)) {
    for (const Vec3& o : clump_) bound_ = std::max(bound_, 1 + o.norm());
  }

  template <class Keep>
  void fill(const SpecPlace& place, const std::string& field, const Vec3& lo, const Vec3& hi, Keep keep) {
    const Real spacing = this->spacing();
    Eigen::Array3d count = ((hi - lo).array() - 2 * r_max_ * bound_) / spacing + 1;
    count = (count + 1e-9).floor();  // a box exactly n grains across holds n
    const Real spheres = count.prod() * std::max<std::size_t>(1, clump_.size());
    if (spheres > kMaxGrains)
      place.fail(field, fmt::format("it holds {:.3g} spheres; at most {} per scene", spheres, kMaxGrains));
    for (int i = 0; i < count.x(); ++i)
      for (int j = 0; j < count.y(); ++j)
        for (int k = 0; k < count.z(); ++k) {
          Vec3 p = lo + Vec3::Constant(r_max_ * bound_) + spacing * Vec3(i, j, k);
          if (keep(p)) add(p);
        }
    if (static_cast<Index>(positions.size()) > kMaxGrains)
      place.fail(field, fmt::format("the grains number {}; at most {} per scene", positions.size(), kMaxGrains));
  }

  /// A grain at lattice point p, moved and sized by the next draws (a clump also turned by them).
  void add(Vec3 p) {
    for (int c = 0; c < 3; ++c) p[c] += 0.01 * r_max_ * (2 * unit_draw(generator_) - 1);
    const Real r = r_min_ + (r_max_ - r_min_) * unit_draw(generator_);
    if (clump_.empty()) {
      add_sphere(p, r);
      return;
    }
    const Real u1 = unit_draw(generator_), u2 = unit_draw(generator_), u3 = unit_draw(generator_);
    const Mat3 R = uniform_rotation(u1, u2, u3);
    for (const Vec3& o : clump_) add_sphere(p + r * (R * o), r);
  }

  /// The lattice spacing, 2 R_max (1 + 2 %).
  Real spacing() const { return 2 * r_max_ * bound_ * 1.02; }
  /// A grain's mean mass: rho 4/3 pi E[r^3], r uniform in [r_min, r_max], E[r^3] = (b^4 - a^4) / (4 (b - a)).
  Real mean_mass() const {
    const Real mean_cube = r_max_ > r_min_ ? (std::pow(r_max_, 4) - std::pow(r_min_, 4)) / (4 * (r_max_ - r_min_))
                                           : r_max_ * r_max_ * r_max_;
    return density_ * 4 * kPi / 3 * mean_cube;
  }

  std::vector<Vec3> positions;
  std::vector<Real> masses, radii;  // clumps: each clump's spheres one after another

 private:
  void add_sphere(const Vec3& p, Real r) {
    positions.push_back(p);
    radii.push_back(r);
    masses.push_back(density_ * 4 * kPi / 3 * r * r * r);
  }

  Real r_min_, r_max_, density_;
  std::mt19937_64 generator_;
  std::vector<Vec3> clump_;  // sphere centres about a clump's centre, in radii (empty: spheres)
  Real bound_ = 1;           // R_max / r_max
};

// "emitter": the grains of every layer it will release, drawn now (after the filled grains) on
// the opening's lattice; layer k holds the opening's points in order (model/particle_emitter.hpp).
ParticleEmitter pour_grains(const EmitterSpec& spec, const SpecPlace& e, GrainLattice& lattice, Real r_max,
                         Real scene_duration) {
  const Real d = lattice.spacing();
  const EmitterOpening opening = place_emitter_opening(spec, e, d, "grain spacing 2.04 r_max", scene_duration);
  ParticleEmitter emitter = particle_emitter_at(opening, d, r_max);
  if (spec.flow_rate) e.fail("flow_rate", "grains are poured at a \"mass_rate\" (kg/s) or a \"speed\" (m/s)");
  if (spec.nozzle_length)
    e.fail("nozzle_length", "grains leave the opening freely; a nozzle holds a stream of fluid or continuum");
  if (spec.speed.has_value() == spec.mass_rate.has_value())
    e.fail("speed", "give exactly one of \"speed\" (m/s) or \"mass_rate\" (kg/s)");
  // A layer of N grains every d / v: the mass rate is N m v / d for grains of mean mass m.
  emitter.speed = spec.speed ? e.number("speed", *spec.speed, Range::positive())
                             : e.number("mass_rate", *spec.mass_rate, Range::positive()) * d /
                                   (emitter.per_layer * lattice.mean_mass());
  emitter.layers = emitter_layers(opening, e, emitter.speed, d);
  if (static_cast<double>(lattice.positions.size()) + static_cast<double>(emitter.layers) * emitter.per_layer > kMaxGrains)
    e.fail("stop", fmt::format("the grains would number {:.3g} with the emitted ones; at most {} per scene",
                               static_cast<double>(lattice.positions.size()) +
                                   static_cast<double>(emitter.layers) * emitter.per_layer,
                               kMaxGrains));
  for (Index k = 0; k < emitter.layers; ++k)
    for (const Vec3& point : opening.points) lattice.add(opening.center + point);
  return emitter;
}

}  // namespace

GranularSpec read_granular(const JsonObject& object) {
  GranularSpec spec;
  spec.regions = read_filled_regions(object);
  if (object.has("emitter")) spec.emitter = read_emitter(object.object("emitter"));
  if (object.has("clump")) {
    const JsonObject clump = object.object("clump");
    spec.clump = GranularClump{};
    spec.clump->spheres = read_integer(clump, "spheres");
    spec.clump->spacing = clump.number("spacing", spec.clump->spacing);
    clump.finish();
  }
  spec.radius = read_optional_number(object, "radius");
  spec.radius_range = read_optional_pair(object, "radius_range");
  if (object.has("seed")) spec.seed = read_integer(object, "seed");
  spec.density = object.number("density", spec.density);
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  spec.contact = read_contact_material(object);
  spec.cohesion = object.number("cohesion", spec.cohesion);
  spec.rolling_resistance = object.number("rolling_resistance", spec.rolling_resistance);
  spec.cohesion_distance = read_optional_number(object, "cohesion_distance");
  spec.contact_compliance = object.number("contact_compliance", spec.contact_compliance);
  spec.contact_damping = object.number("contact_damping", spec.contact_damping);
  return spec;
}

void add_granular(const GranularSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  if (spec.radius.has_value() == spec.radius_range.has_value())
    place.fail("radius", "give exactly one of \"radius\" (m) or \"radius_range\" ([min, max] in m, polydisperse)");
  Real r_min = 0, r_max = 0;
  if (spec.radius) {
    r_min = r_max = place.number("radius", *spec.radius, Range::positive());
  } else {
    const Vec2 r = place.pair("radius_range", *spec.radius_range, Range::positive());
    if (r.x() > r.y()) place.fail("radius_range", "the smallest radius must not exceed the largest");
    r_min = r.x();
    r_max = r.y();
  }
  const Real density = place.number("density", spec.density, Range::positive());
  if (spec.regions.empty() && !spec.emitter)
    place.fail("blocks", "a granular object needs a block {\"min\", \"max\"}, cylinder {\"base\", \"radius\", \"height\"} "
                         "or sphere {\"center\", \"radius\"} to fill, a closed \"mesh\" to fill, or an \"emitter\" to "
                         "pour its grains");

  std::vector<Vec3> clump;
  if (spec.clump) {
    const SpecPlace c = place.at("clump");
    const int spheres = c.integer("spheres", spec.clump->spheres, 2, 4);
    const Real spacing = c.number("spacing", spec.clump->spacing, Range::positive());
    if (spacing >= 2) c.fail("spacing", "the spheres of a clump must overlap: their centre distance is below 2 radii");
    if (spec.emitter) place.fail("emitter", "an emitter pours single grains; clumps fill blocks, cylinders, spheres or meshes");
    clump = clump_offsets(spheres, spacing);
  }
  GrainLattice lattice(r_min, r_max, density, static_cast<std::uint64_t>(spec.seed), clump);
  const Real diameter = lattice.spacing() / 1.02;  // of a grain or a clump's bounding sphere
  fill_regions(spec.regions, place, ctx, {diameter, diameter / 2, "grain diameter"},
               [&](const SpecPlace& at, const std::string& field, const Vec3& lo, const Vec3& hi, auto keep) {
                 lattice.fill(at, field, lo, hi, keep);
               },
               [&] { return lattice.positions.size(); });
  const Index filled = static_cast<Index>(lattice.positions.size());
  ParticleEmitter emitter;
  if (spec.emitter) emitter = pour_grains(*spec.emitter, place.at("emitter"), lattice, r_max, ctx.duration);
  const std::vector<Vec3>& positions = lattice.positions;
  const std::vector<Real>& masses = lattice.masses;
  const std::vector<Real>& radii = lattice.radii;
  set_contact_material(spec.contact, place, info);
  info.cohesion = place.number("cohesion", spec.cohesion, Range::non_negative());
  info.rolling_resistance = place.number("rolling_resistance", spec.rolling_resistance, Range::non_negative());
  info.cohesion_distance = spec.cohesion_distance
                               ? place.number("cohesion_distance", *spec.cohesion_distance, Range::non_negative())
                               : 0.1 * r_max;
  if (info.cohesion_distance > r_max)
    place.fail("cohesion_distance", fmt::format("a bond may reach at most the largest radius, {} m", r_max));
  if (spec.cohesion_distance && info.cohesion == 0)
    place.fail("cohesion_distance", "a bond's reach needs a bond: give \"cohesion\" (N) too");
  if (info.cohesion == 0) info.cohesion_distance = 0;  // dry grains reach no further than they touch
  info.contact_spring = {place.number("contact_compliance", spec.contact_compliance, Range::non_negative()),
                         place.number("contact_damping", spec.contact_damping, Range::non_negative())};
  if (info.contact_spring.damping > 0 && !info.contact_spring.soft())
    place.fail("contact_damping", "a dashpot needs a spring: give \"contact_compliance\" (m/N) too");
  info.kind = ObjectKind::granular;
  info.self_collision = true;
  info.fluid_coupling = false;
  add_particles(ctx, info, positions, masses, r_max, r_max, place.vector("velocity", spec.velocity));
  Model& m = ctx.model;
  for (Index p = info.particle_begin; p < info.particle_end; ++p) {
    // A solid sphere: I = 2/5 m r^2. A clump's spheres do not turn on their own: the clump turns
    // as its cluster's fit.
    if (!spec.clump)
      m.particle_inv_inertia[p] = 2.5 * m.particle_inv_mass[p] / (radii[p - info.particle_begin] * radii[p - info.particle_begin]);
    m.particle_radius[p] = radii[p - info.particle_begin];
    m.particle_collider_gap[p] = radii[p - info.particle_begin];
    m.contact_particle.push_back(p);
  }
  if (spec.clump) {  // each clump a rigid shape-matching cluster
    info.clump_size = static_cast<Index>(clump.size());
    const Index object = static_cast<Index>(m.objects.size());
    const Index size = static_cast<Index>(clump.size());
    std::vector<Index> members(size);
    for (Index first = 0; first < static_cast<Index>(lattice.positions.size()); first += size) {
      for (Index k = 0; k < size; ++k) members[k] = info.particle_begin + first + k;
      m.shape_matching.add(members, m.particle_rest_position, m.particle_mass, 0, object);
    }
  }
  if (spec.emitter) {
    emitter.object = static_cast<Index>(m.objects.size());  // the object being added
    emitter.first = info.particle_begin + filled;
    for (Index p = emitter.first; p < info.particle_end; ++p) ctx.initial_velocity[p] = Vec3::Zero();  // set when released
    m.particle_emitters.push_back(emitter);
  }
}

}  // namespace moreau
