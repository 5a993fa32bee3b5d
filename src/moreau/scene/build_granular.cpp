// "kind": "granular" objects: grains as particles on a lattice filling boxes, each touching the
// others, colliders, rigid bodies and rods through the particle contacts (with friction,
// restitution and cohesion); polydisperse radii drawn from a seeded generator.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "moreau/scene/spec_builders.hpp"

namespace moreau {

namespace {

// A uniform number in [0, 1) from the generator's raw 64 bits (the same on every platform,
// unlike the standard distributions).
Real unit_draw(std::mt19937_64& generator) { return static_cast<Real>(generator() >> 11) * 0x1.0p-53; }

}  // namespace

GranularSpec read_granular(const JsonObject& object) {
  GranularSpec spec;
  for (const JsonObject& block : object.object_list("blocks")) spec.blocks.push_back(read_block(block));
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
  if (spec.blocks.empty()) place.fail("blocks", "a granular object needs at least one block {\"min\", \"max\"} to fill");

  // A cubic lattice of spacing 2 r_max (1 + 2 %), each grain moved by up to 1 % of r_max in each
  // direction so that no column stands balanced on an exact stack; grains never overlap at rest.
  const Real spacing = 2 * r_max * 1.02;
  std::mt19937_64 generator(static_cast<std::uint64_t>(spec.seed));
  std::vector<Vec3> positions;
  std::vector<Real> masses, radii;
  constexpr Index kMaxGrains = 50'000'000;
  for (size_t b = 0; b < spec.blocks.size(); ++b) {
    const SpecPlace block = place.at(fmt::format("blocks[{}]", b));
    const Vec3 lo = block.vector("min", spec.blocks[b].min), hi = block.vector("max", spec.blocks[b].max);
    if ((hi.array() - lo.array() < 2 * r_max * (1 - 1e-9)).any())
      block.fail("max", fmt::format("the block must be at least one grain diameter ({} m) across in every direction", 2 * r_max));
    Eigen::Array3d count = ((hi - lo).array() - 2 * r_max) / spacing + 1;
    count = (count + 1e-9).floor();  // a block exactly n grains across holds n
    if (count.prod() > kMaxGrains)
      block.fail("max", fmt::format("the block holds {:.3g} grains; at most {} per scene", count.prod(), kMaxGrains));
    for (int i = 0; i < count.x(); ++i)
      for (int j = 0; j < count.y(); ++j)
        for (int k = 0; k < count.z(); ++k) {
          Vec3 p = lo + Vec3::Constant(r_max) + spacing * Vec3(i, j, k);
          for (int c = 0; c < 3; ++c) p[c] += 0.01 * r_max * (2 * unit_draw(generator) - 1);
          const Real r = r_min + (r_max - r_min) * unit_draw(generator);
          positions.push_back(p);
          radii.push_back(r);
          masses.push_back(density * 4 * kPi / 3 * r * r * r);
        }
  }
  if (static_cast<Index>(positions.size()) > kMaxGrains)
    place.fail("blocks", fmt::format("the blocks hold {} grains; at most {} per scene", positions.size(), kMaxGrains));
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
    // A solid sphere: I = 2/5 m r^2.
    m.particle_inv_inertia[p] = 2.5 * m.particle_inv_mass[p] / (radii[p - info.particle_begin] * radii[p - info.particle_begin]);
    m.particle_radius[p] = radii[p - info.particle_begin];
    m.particle_collider_gap[p] = radii[p - info.particle_begin];
    m.contact_particle.push_back(p);
  }
}

}  // namespace moreau
