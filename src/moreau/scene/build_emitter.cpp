// "emitter" of fluids and granular objects: the opening's lattice points, the flow direction
// and the window of time in which layers are released (fluid_emitter.hpp, model/particle_emitter.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "moreau/geometry/lattice_openings.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

EmitterSpec read_emitter(const JsonObject& e) {
  EmitterSpec spec;
  spec.center = to_vector3(e.vec3("center"));
  spec.direction = to_vector3(e.vec3("direction"));
  spec.shape = e.choice("shape", {"disc", "rectangle"});
  if (spec.shape == "disc") {
    spec.radius = e.number("radius");
  } else {
    const Vec2 size = e.vec2("size", Range::any());
    spec.size = {size.x(), size.y()};
    spec.tangent = read_vector(e, "tangent", spec.tangent);
  }
  spec.speed = read_optional_number(e, "speed");
  spec.flow_rate = read_optional_number(e, "flow_rate");  // fluids take this one,
  spec.mass_rate = read_optional_number(e, "mass_rate");  // grains this one: their builders say so
  spec.start = e.number("start", spec.start);
  spec.stop = read_optional_number(e, "stop");
  spec.nozzle_length = read_optional_number(e, "nozzle_length");  // fluids only
  e.finish();
  return spec;
}

EmitterOpening place_emitter_opening(const EmitterSpec& spec, const SpecPlace& e, Real d, const std::string& spacing_name,
                                     Real scene_duration) {
  EmitterOpening o;
  o.center = e.vector("center", spec.center);
  const Vec3 direction = e.vector("direction", spec.direction);
  if (!(direction.norm() > 0)) e.fail("direction", "the flow direction must be a non-zero vector");
  o.normal = direction.normalized();
  if (e.choice("shape", spec.shape, {"disc", "rectangle"}) == "disc") {
    if (spec.size != Vector2{0, 0} || spec.tangent != Vector3{0, 0, 0})
      e.fail(spec.size != Vector2{0, 0} ? "size" : "tangent", "a disc takes a \"radius\"; size and tangent are a rectangle's");
    const Real radius = e.number("radius", spec.radius, Range::positive());
    if (radius < 0.5 * d)
      e.fail("radius", fmt::format("the disc's radius must be at least half the {} ({} m) to hold a particle", spacing_name, d));
    o.points = disc_opening(o.normal, radius, d);
  } else {
    if (spec.radius != 0) e.fail("radius", "a rectangle takes a \"size\" (and a \"tangent\"); the radius is a disc's");
    const Vec2 size = e.pair("size", spec.size, Range::positive());
    if (size.minCoeff() < d) e.fail("size", fmt::format("each side must be at least one {} = {} m", spacing_name, d));
    o.points = rectangle_opening(o.normal, e.vector("tangent", spec.tangent), size.x(), size.y(), d);
  }
  o.start = e.number("start", spec.start, Range::non_negative());
  o.stop = e.number("stop", spec.stop.value_or(scene_duration), Range::non_negative());
  if (o.stop < o.start) e.fail("stop", fmt::format("stop must not precede start ({} s)", o.start));
  return o;
}

Index emitter_layers(const EmitterOpening& opening, const SpecPlace& e, Real speed, Real d) {
  // Checked as a real number before the cast to Index (32 bits).
  const Real layers = std::floor((opening.stop - opening.start) * speed / d + 1e-9) + 1;
  constexpr Real kMaxEmitted = 5e7;
  if (layers * opening.points.size() > kMaxEmitted)
    e.fail("stop", fmt::format("the emitter would release {:.3g} particles by t = {} s (limit {:.0g}); lower the rate "
                               "or the stop time", layers * opening.points.size(), opening.stop, kMaxEmitted));
  return static_cast<Index>(layers);
}

ParticleEmitter particle_emitter_at(const EmitterOpening& opening, Real d, Real max_radius) {
  ParticleEmitter emitter;
  emitter.center = opening.center;
  emitter.normal = opening.normal;
  emitter.spacing = d;
  emitter.per_layer = static_cast<Index>(opening.points.size());
  emitter.start = opening.start;
  emitter.max_radius = max_radius;
  for (const Vec3& point : opening.points) emitter.reach = std::max(emitter.reach, point.norm());
  emitter.reach += max_radius;
  return emitter;
}

}  // namespace moreau
