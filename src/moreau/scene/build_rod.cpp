// "kind": "rod" objects: a Cosserat rod as a chain of rigid segments (rods/rod_model.hpp) joined by
// rod joints (constraints/joints/rod_joint.cpp), with its section, material and end conditions.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "moreau/collision/narrow_phase_parts.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

namespace {

const std::vector<std::string> kRodEnds{"free", "clamped", "pinned"};

std::vector<Vector3> read_points(const JsonObject& object) {
  const auto& raw = object.raw("points");
  const bool numeric = raw.is_array() && std::all_of(raw.begin(), raw.end(), [](const auto& p) {
                         return p.is_array() && p.size() == 3 &&
                                std::all_of(p.begin(), p.end(), [](const auto& v) { return v.is_number(); });
                       });
  if (!numeric) object.fail("points", "expected a list of points [[x, y, z], ...] in m");
  std::vector<Vector3> points;
  for (const auto& p : raw) points.push_back({p[0].get<Real>(), p[1].get<Real>(), p[2].get<Real>()});
  return points;
}

// The section: area, the second moments about its two axes, the torsion constant and the radius
// of the capsules that collide for it. Axis 1 is the segment's x (the "normal"), axis 2 its z.
struct Section {
  Real area = 0;
  Real inertia_about_x = 0, inertia_about_z = 0;  // m^4: I_x = pi a b^3 / 4 (b the half-width along z)
  Real torsion = 0;                               // m^4: J = pi a^3 b^3 / (a^2 + b^2), pi r^4 / 2 round
  Real half_x = 0, half_z = 0;                    // m: the half-widths a (along x) and b (along z)
  Real collision_radius = 0;                      // m: the larger half-width
};

Section section(const RodSpec& spec, const SpecPlace& place) {
  if (spec.radius.has_value() == spec.radii.has_value())
    place.fail("radius", "give exactly one of \"radius\" (m, a round section) or \"radii\" ([a, b] in m, an ellipse)");
  Section s;
  if (spec.radius) {
    s.half_x = s.half_z = place.number("radius", *spec.radius, Range::positive());
  } else {
    const Vec2 r = place.pair("radii", *spec.radii, Range::positive());
    s.half_x = r.x();
    s.half_z = r.y();
  }
  const Real a = s.half_x, b = s.half_z;
  s.area = kPi * a * b;
  s.inertia_about_x = kPi * a * b * b * b / 4;
  s.inertia_about_z = kPi * a * a * a * b / 4;
  s.torsion = kPi * a * a * a * b * b * b / (a * a + b * b);
  s.collision_radius = std::max(a, b);
  return s;
}

// The centreline at rest: the helix sampled at `segments` equal steps of its angle (equal arc
// lengths), or the polyline as given or resampled at equal arc lengths.
std::vector<Vec3> centreline(const RodSpec& spec, const SpecPlace& place) {
  if (spec.helix && !spec.points.empty()) place.fail("points", "give either \"points\" (a polyline) or \"helix\", not both");
  if (spec.helix) {
    const SpecPlace h = place.at("helix");
    const RodHelix& helix = *spec.helix;
    const Vec3 center = h.vector("center", helix.center), axis_in = h.vector("axis", helix.axis);
    if (axis_in.norm() <= 0) h.fail("axis", "the axis must not be zero");
    const Real radius = h.number("radius", helix.radius, Range::positive());
    const Real pitch = h.number("pitch", helix.pitch);
    const Real turns = h.number("turns", helix.turns, Range::positive());
    const int n = spec.segments ? place.integer("segments", *spec.segments, 1, 100000)
                                : std::max(1, static_cast<int>(std::ceil(16 * turns)));
    const Vec3 axis = axis_in.normalized();
    const Vec3 across = (std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitZ()).cross(axis).normalized();
    const Vec3 other = axis.cross(across);
    std::vector<Vec3> points;
    for (int k = 0; k <= n; ++k) {
      const Real angle = 2 * kPi * turns * k / n;
      points.push_back(center + radius * (std::cos(angle) * across + std::sin(angle) * other) +
                       pitch * turns * (Real(k) / n) * axis);
    }
    return points;
  }
  if (spec.points.size() < 2) place.fail("points", "a rod needs a polyline of at least two points, or a \"helix\"");
  std::vector<Vec3> polyline;
  for (const Vector3& p : spec.points) polyline.push_back(place.vector("points", p));
  std::vector<Real> arc{0};
  for (size_t k = 1; k < polyline.size(); ++k) {
    const Real length = (polyline[k] - polyline[k - 1]).norm();
    if (length <= 0) place.fail("points", fmt::format("points {} and {} coincide; a rod's points must differ", k - 1, k));
    arc.push_back(arc.back() + length);
  }
  if (!spec.segments) return polyline;
  const int n = place.integer("segments", *spec.segments, 1, 100000);
  std::vector<Vec3> points;
  size_t edge = 1;
  for (int k = 0; k <= n; ++k) {
    const Real s = arc.back() * k / n;
    while (edge + 1 < arc.size() && arc[edge] < s) ++edge;
    const Real t = std::clamp((s - arc[edge - 1]) / (arc[edge] - arc[edge - 1]), Real(0), Real(1));
    points.push_back((1 - t) * polyline[edge - 1] + t * polyline[edge]);
  }
  return points;
}

// The segments' rest orientations: body y along the segment, body x the section's first axis,
// carried from segment to segment by the smallest rotation between their tangents (parallel
// transport: no rest twist).
std::vector<Quat> segment_frames(const std::vector<Vec3>& points, const RodSpec& spec, const SpecPlace& place) {
  std::vector<Quat> frames;
  Vec3 tangent = (points[1] - points[0]).normalized();
  Vec3 normal = std::abs(tangent.y()) < 0.9 ? tangent.cross(Vec3::UnitY()) : tangent.cross(Vec3::UnitX());
  if (spec.normal) {
    normal = place.vector("normal", *spec.normal);
    normal -= normal.dot(tangent) * tangent;
    if (normal.norm() < 1e-9 * std::max(Real(1), place.vector("normal", *spec.normal).norm()))
      place.fail("normal", "the normal must not lie along the rod's first segment");
  }
  normal.normalize();
  for (size_t k = 0; k + 1 < points.size(); ++k) {
    const Vec3 t = (points[k + 1] - points[k]).normalized();
    if (t.dot(tangent) < -1 + 1e-9)
      place.fail("points", fmt::format("the centreline turns back on itself at point {}; a rod's segments may not reverse", k));
    normal = Quat::FromTwoVectors(tangent, t) * normal;
    normal = (normal - normal.dot(t) * t).normalized();
    tangent = t;
    Mat3 R;
    R << normal, t, normal.cross(t);
    frames.push_back(Quat(R).normalized());
  }
  return frames;
}

// The joint frame in a segment's body frame: x along the rod (body y), y the body's z, z the body's x.
Quat junction_frame() {
  Mat3 R;
  R << Vec3::UnitY(), Vec3::UnitZ(), Vec3::UnitX();
  return Quat(R);
}

struct RodMaterial {
  Real E = 0, G = 0;
  Real E_bending = 0;  // a stranded rope or cable bends far more easily than a solid rod of its section
};

// The compliances of a junction standing for `length` of the rod (rod_joint.cpp).
void set_junction_compliance(Joint& joint, Real length, const Section& s, const RodMaterial& m) {
  joint.rod_compliance = length * Vec3(1 / (m.E * s.area), 1 / (m.G * s.area), 1 / (m.G * s.area));
  // Joint y is the body's z and joint z the body's x.
  joint.rod_angular_compliance =
      length * Vec3(1 / (m.G * s.torsion), 1 / (m.E_bending * s.inertia_about_z), 1 / (m.E_bending * s.inertia_about_x));
}

}  // namespace

RodSpec read_rod(const JsonObject& object) {
  RodSpec spec;
  if (object.has("points")) spec.points = read_points(object);
  if (object.has("helix")) {
    const JsonObject h = object.object("helix");
    RodHelix helix;
    helix.center = read_vector(h, "center", helix.center);
    helix.axis = read_vector(h, "axis", helix.axis);
    helix.radius = h.number("radius");
    helix.pitch = h.number("pitch", helix.pitch);
    helix.turns = h.number("turns", helix.turns);
    h.finish();
    spec.helix = helix;
  }
  if (object.has("segments")) spec.segments = read_integer(object, "segments");
  spec.normal = read_optional_vector(object, "normal");
  spec.radius = read_optional_number(object, "radius");
  spec.radii = read_optional_pair(object, "radii");
  spec.youngs_modulus = read_optional_number(object, "youngs_modulus");
  spec.shear_modulus = read_optional_number(object, "shear_modulus");
  spec.poisson_ratio = read_optional_number(object, "poisson_ratio");
  spec.bending_modulus = read_optional_number(object, "bending_modulus");
  spec.density = object.number("density", spec.density);
  if (object.has("start")) spec.start = object.string("start");
  if (object.has("end")) spec.end = object.string("end");
  spec.damping_time = object.number("damping_time", spec.damping_time);
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  spec.contact = read_contact_material(object);
  spec.self_collision = object.boolean("self_collision", spec.self_collision);
  return spec;
}

void add_rod(const RodSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  Model& model = ctx.model;
  RigidBodyModel& m = model.rigid;
  const Section s = section(spec, place);
  RodMaterial material;
  material.E = place.required("youngs_modulus", spec.youngs_modulus, Range::positive());
  if (spec.shear_modulus && spec.poisson_ratio)
    place.fail("shear_modulus", "give either \"shear_modulus\" (Pa) or \"poisson_ratio\", not both");
  material.G = spec.shear_modulus
                   ? place.number("shear_modulus", *spec.shear_modulus, Range::positive())
                   : material.E / (2 * (1 + place.number("poisson_ratio", spec.poisson_ratio.value_or(0.3),
                                                         Range::open(-1, 0.5))));
  material.E_bending = spec.bending_modulus ? place.number("bending_modulus", *spec.bending_modulus, Range::positive())
                                            : material.E;
  const Real density = place.number("density", spec.density, Range::positive());
  const Real damping = place.number("damping_time", spec.damping_time, Range::non_negative());
  const std::string& start = place.choice("start", spec.start, kRodEnds);
  const std::string& end = place.choice("end", spec.end, kRodEnds);
  set_contact_material(spec.contact, place, info);
  const Vec3 velocity = place.vector("velocity", spec.velocity);

  const std::vector<Vec3> points = centreline(spec, place);
  const std::vector<Quat> frames = segment_frames(points, spec, place);
  const Index segments = static_cast<Index>(frames.size());
  const Index object = static_cast<Index>(model.objects.size());

  RodModel rod;
  rod.object = object;
  rod.first_body = m.count();
  rod.segments = segments;
  rod.rest_points = points;
  Real shortest = std::numeric_limits<Real>::infinity();
  for (Index k = 0; k < segments; ++k) {
    const Real length = (points[k + 1] - points[k]).norm();
    shortest = std::min(shortest, length);
    rod.segment_length.push_back(length);
    // A solid elliptic cylinder of the segment's length: the capsule that collides for it only
    // shapes its contacts.
    const Real mass = density * s.area * length;
    const Vec3 inertia = mass * Vec3(s.half_z * s.half_z / 4 + length * length / 12,
                                     (s.half_x * s.half_x + s.half_z * s.half_z) / 4,
                                     s.half_x * s.half_x / 4 + length * length / 12);
    BodyDescription body;
    body.shape = make_capsule(s.collision_radius, length / 2);
    body.object = object;
    body.mass = mass;
    body.inertia = inertia;
    body.static_friction = info.static_friction;
    body.dynamic_friction = info.dynamic_friction;
    body.restitution = info.restitution;
    body.adhesion = info.adhesion;
    body.position = 0.5 * (points[k] + points[k + 1]);
    body.orientation = frames[k];
    body.velocity = velocity;
    m.add(std::move(body));
  }

  // Junctions: segment k's end meets segment k + 1's start; each stands for the length between
  // the two centres. Their frames coincide at rest, which keeps the rest curvature.
  auto joint_named = [&](const std::string& what) {
    Joint j;
    j.name = fmt::format("{}.{}", info.name, what);
    j.damping_time = damping;
    return j;
  };
  auto body_end = [&](Index k, Real along) {
    JointEnd e;
    e.kind = BodyEndKind::body;
    e.index = rod.first_body + k;
    e.anchor = Vec3(0, along, 0);
    return e;
  };
  rod.first_joint = static_cast<Index>(model.joints.size());
  for (Index k = 0; k + 1 < segments; ++k) {
    Joint j = joint_named(fmt::format("junction{}", k));
    j.type = JointType::rod;
    j.ends = {body_end(k, rod.segment_length[k] / 2), body_end(k + 1, -rod.segment_length[k + 1] / 2)};
    j.ends[0].frame = junction_frame();
    j.ends[1].frame = (frames[k + 1].conjugate() * frames[k] * junction_frame()).normalized();
    set_junction_compliance(j, (rod.segment_length[k] + rod.segment_length[k + 1]) / 2, s, material);
    model.joints.push_back(std::move(j));
  }
  // Ends held where they are: clamped keeps the end's position and direction through a junction
  // with the world for the half segment beyond the end's centre; pinned only its position (the
  // junction's stretch-shear rows).
  auto hold = [&](const std::string& mode, const char* which, Index k, Real along) {
    if (mode == "free") return;
    Joint j = joint_named(which);
    const Real half = rod.segment_length[k] / 2;
    JointEnd world;
    world.anchor = m.initial_position[k + rod.first_body] + frames[k] * Vec3(0, along, 0);
    world.frame = (frames[k] * junction_frame()).normalized();
    JointEnd body = body_end(k, along);
    body.frame = junction_frame();
    // The world end comes first at the start (the rod runs from it), last at the end.
    j.ends = along < 0 ? std::array<JointEnd, 2>{world, body} : std::array<JointEnd, 2>{body, world};
    j.type = JointType::rod;
    j.rod_pinned = mode == "pinned";
    set_junction_compliance(j, half, s, material);
    (along < 0 ? rod.start_joint : rod.end_joint) = static_cast<Index>(model.joints.size());
    model.joints.push_back(std::move(j));
  };
  hold(start, "start", 0, -rod.segment_length[0] / 2);
  hold(end, "end", segments - 1, rod.segment_length[segments - 1] / 2);
  rod.joint_count = static_cast<Index>(model.joints.size()) - rod.first_joint;

  // Segments that touch at rest never collide: neighbours, those within the reach of the section
  // along the rod (1 + ceil(2 r / l) apart), and any others whose capsules overlap in the rest
  // shape (a closed ring, tight helix turns, a folded polyline). The rest collide with each other
  // when self_collision is on.
  if (spec.self_collision) {
    const Index reach = 1 + static_cast<Index>(std::ceil(2 * s.collision_radius / shortest));
    const Real touching = 2 * s.collision_radius * (1 + 1e-9);
    for (Index a = 0; a < segments; ++a)
      for (Index b = a + 1; b < segments; ++b) {
        bool apart = b - a > reach;
        const Vec3 ca = 0.5 * (points[a] + points[a + 1]), cb = 0.5 * (points[b] + points[b + 1]);
        const bool far = (ca - cb).norm() > 0.5 * (rod.segment_length[a] + rod.segment_length[b]) + touching;
        if (apart && !far) {
          Vec3 on_a, on_b;
          narrow::closest_points_of_segments(points[a], points[a + 1], points[b], points[b + 1], on_a, on_b);
          apart = (on_a - on_b).norm() > touching;
        }
        if (!apart) m.pairs_without_contact.push_back({rod.first_body + a, rod.first_body + b});
      }
  } else {
    m.body_contact_group.resize(m.count(), -1);
    for (Index k = 0; k < segments; ++k) m.body_contact_group[rod.first_body + k] = object;
  }

  info.kind = ObjectKind::rod;
  info.fluid_coupling = false;  // rods are not sampled for the particle fluids
  info.body = rod.first_body;
  info.body_count = segments;
  info.rod = static_cast<Index>(model.rods.size());
  model.rods.push_back(std::move(rod));
}

}  // namespace moreau
