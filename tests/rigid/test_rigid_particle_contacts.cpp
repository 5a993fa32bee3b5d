// Contacts between particles (cloth, soft bodies) and rigid bodies, and the point queries they
// use: nearest surface points against their defining properties, the weight a soft body puts on
// a box passing through the box to the ground, and momentum across a particle-body impact.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "moreau/collision/point_query.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

std::vector<Shape> query_shapes() {
  std::vector<Vec3> points;
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> u(-0.4, 0.4);
  for (int k = 0; k < 40; ++k) points.emplace_back(u(rng), 0.5 * u(rng), u(rng));
  Shape hull;
  hull.type = ShapeType::convex_hull;
  hull.polyhedron = convex_hull(points);
  return {make_sphere(0.3), make_box(Vec3(0.3, 0.2, 0.1)), make_capsule(0.15, 0.25), make_cylinder(0.2, 0.3),
          hull, make_plane()};
}

// Brute-force distance from p to a polyhedron's surface: the nearest of dense samples of every
// face (a fan of triangles sampled on a 60 x 60 barycentric grid), so it is an upper bound within
// the sample spacing.
Real sampled_polyhedron_distance(const ConvexPolyhedron& poly, const Vec3& p) {
  Real best = 1e300;
  constexpr int n = 60;
  for (const auto& face : poly.faces)
    for (size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3 &a = poly.vertices[face[0]], &b = poly.vertices[face[k]], &c = poly.vertices[face[k + 1]];
      for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j)
          best = std::min(best, (p - (a + (b - a) * i / Real(n) + (c - a) * j / Real(n))).norm());
    }
  return best;
}

TEST(PointQuery, NearestSurfacePointIsOnTheSurfaceAndTheDistanceGradientIsTheNormal) {
  // For every shape and 300 points in and around it:
  //  - p = s + d n (the point, the surface point and the normal agree), |n| = 1, to round-off;
  //  - s lies on the surface: its own distance is 0 (1e-12 m);
  //  - d is differentiable with gradient n (the distance to a convex set is C1 outside it, and
  //    inside almost everywhere): central differences with step 1e-6 m agree to 1e-6.
  //  - hulls: d matches a dense sampling of the faces to its spacing (outside points).
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> u(-0.6, 0.6);
  for (const Shape& shape : query_shapes()) {
    for (int k = 0; k < 300; ++k) {
      const Vec3 p(u(rng), u(rng), u(rng));
      const SurfacePoint s = nearest_surface_point(shape, p);
      SCOPED_TRACE(fmt::format("shape {} point ({}, {}, {})", static_cast<int>(shape.type), p.x(), p.y(), p.z()));
      EXPECT_NEAR(s.normal.norm(), 1, 1e-12);
      EXPECT_LT((s.point + s.distance * s.normal - p).norm(), 1e-12);
      EXPECT_LT(std::abs(nearest_surface_point(shape, s.point).distance), 1e-12);
      const Real e = 1e-6;
      Vec3 gradient;
      for (int a = 0; a < 3; ++a) {
        Vec3 step = Vec3::Zero();
        step[a] = e;
        gradient[a] = (nearest_surface_point(shape, p + step).distance - nearest_surface_point(shape, p - step).distance) /
                      (2 * e);
      }
      EXPECT_LT((gradient - s.normal).norm(), 1e-6);
      if (shape.type == ShapeType::convex_hull && s.distance > 0) {
        EXPECT_NEAR(s.distance, sampled_polyhedron_distance(shape.polyhedron, p), 0.01);
      }
    }
  }
}

// A 0.6 x 0.2 x 0.6 m box (500 kg/m^3, 36 kg) on the ground with an 8 kg soft cube on top.
std::string soft_cube_on_box(const std::string& settings) {
  return fmt::format(R"({{"name": "stack", "settings": {{{}}},
    "objects": [
      {{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
      {{"name": "box", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.3, 0.1, 0.3]}},
        "position": [0, 0.1, 0], "density": 500}},
      {{"name": "jelly", "kind": "soft_body",
        "mesh": {{"type": "box", "min": [-0.1, 0.21, -0.1], "max": [0.1, 0.41, 0.1], "cells": [4, 4, 4]}},
        "material": {{"model": "neo_hookean", "youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000,
                     "damping": 0.002}}}}]}})",
                     settings);
}

TEST(ParticleBodyContacts, SoftBodyWeightPassesThroughTheBoxToTheGround) {
  // After 2 s at rest the ground pushes the box with the weight of both, (36 + 8) kg g = 431.6 N;
  // the ground's force is the box's ground multipliers over h^2 in the last substep. Everything is
  // at rest, so what is left is the solver's residual: 0.5 % allows for it. The cube rests on the
  // box's top face (y = 0.2 m) without sinking in (1e-5 m) and the box does not drift.
  Scene s = scene_from_json(soft_cube_on_box(R"("substeps": 20)"));
  run_steps(s, 120);
  const Model& m = s.model;
  const Real h = m.settings.dt / m.settings.substeps;
  const Index box = m.objects[m.find_object("box")].body;
  Real lambda = 0;
  for (const RigidManifold& mf : s.state.rigid_contacts.manifolds)
    if (mf.body_a == box || mf.body_b == box)
      for (Index i = mf.first; i < mf.first + mf.count; ++i) lambda += s.state.rigid_contacts.points[i].lambda_normal;
  const Real weight = (36 + 8) * 9.81;
  std::printf("ground force %.4f N against the weight %.4f N\n", lambda / (h * h), weight);
  EXPECT_NEAR(lambda / (h * h), weight, 0.005 * weight);
  const ObjectInfo& jelly = m.objects[m.find_object("jelly")];
  Real lowest = 1e9;
  for (Index p = jelly.particle_begin; p < jelly.particle_end; ++p) lowest = std::min(lowest, s.state.position[p].y());
  EXPECT_GT(lowest, 0.2 - 1e-5);
  EXPECT_LT(lowest, 0.2 + 1e-5);
  EXPECT_LT((s.state.rigid.position[box] - Vec3(0, 0.1, 0)).norm(), 1e-4);
}

TEST(ParticleBodyContacts, ImpactOfASoftBodyOnAFreeBoxKeepsLinearMomentum) {
  // No gravity, no colliders: a soft cube at 2 m/s hits a free box off-centre (it turns), with
  // friction 0.5. Every contact correction is an equal and opposite pair, so the total momentum
  // stays what it was to round-off (1e-12 relative), while the box takes a good part of it.
  Scene s = scene_from_json(R"({"name": "impact", "settings": {"substeps": 20, "gravity": [0, 0, 0]},
    "objects": [
      {"name": "box", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.2, 0.2, 0.2]},
       "position": [0, 0, 0], "density": 100, "friction": 0.5},
      {"name": "jelly", "kind": "soft_body", "velocity": [2, 0, 0], "friction": 0.5,
       "mesh": {"type": "box", "min": [-0.5, 0.05, -0.1], "max": [-0.3, 0.25, 0.1], "cells": [3, 3, 3]},
       "material": {"model": "neo_hookean", "youngs_modulus": 5e4, "poisson_ratio": 0.3, "density": 1000}}]})");
  const Model& m = s.model;
  const Index box = m.objects[m.find_object("box")].body;
  auto momentum = [&] {
    Vec3 p = m.rigid.body_mass[box] * s.state.rigid.velocity[box];
    for (Index q = 0; q < m.particle_count(); ++q) p += m.particle_mass[q] * s.state.velocity[q];
    return p;
  };
  const Vec3 initial = momentum();
  run_steps(s, 30);
  std::printf("momentum change %.3g of %.3g kg m/s; box took %.3g\n", (momentum() - initial).norm(), initial.norm(),
              m.rigid.body_mass[box] * s.state.rigid.velocity[box].x());
  EXPECT_LT((momentum() - initial).norm(), 1e-12 * initial.norm());
  EXPECT_GT(m.rigid.body_mass[box] * s.state.rigid.velocity[box].x(), 0.3 * initial.x());
  EXPECT_GT(s.state.rigid.angular_velocity[box].norm(), 0.1);
}

}  // namespace
}  // namespace moreau
