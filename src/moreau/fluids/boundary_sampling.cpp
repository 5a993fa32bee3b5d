#include "moreau/fluids/boundary_sampling.hpp"

#include <cmath>

#include "moreau/geometry/neighbor_search.hpp"

namespace moreau {

namespace {

// Points of the unit sphere, nearly evenly spread (Fibonacci / golden-angle lattice).
std::vector<Vec3> fibonacci_sphere(int count) {
  std::vector<Vec3> points;
  const Real golden = kPi * (3 - std::sqrt(5.0));
  for (int k = 0; k < count; ++k) {
    const Real y = 1 - (k + 0.5) * 2 / count;
    const Real rho = std::sqrt(std::max(0.0, 1 - y * y));
    points.emplace_back(rho * std::cos(golden * k), y, rho * std::sin(golden * k));
  }
  return points;
}

// The surface of a box: lattice points of [-half, half] with at least one index on a face.
std::vector<Vec3> box_surface(const Vec3& half, Real spacing) {
  int n[3];
  for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::ceil(2 * half[a] / spacing)));
  std::vector<Vec3> points;
  for (int i = 0; i <= n[0]; ++i)
    for (int j = 0; j <= n[1]; ++j)
      for (int k = 0; k <= n[2]; ++k) {
        const bool on_face = i == 0 || i == n[0] || j == 0 || j == n[1] || k == 0 || k == n[2];
        if (!on_face) continue;
        points.emplace_back(-half.x() + 2 * half.x() * i / n[0], -half.y() + 2 * half.y() * j / n[1],
                            -half.z() + 2 * half.z() * k / n[2]);
      }
  return points;
}

}  // namespace

std::vector<Vec3> sample_collider_surface(const Collider& c, Real spacing, Real depth, const Vec3& plane_center,
                                          Real plane_half_size) {
  // Moving the surface into the solid grows a container and shrinks a solid (not below half size).
  const Real grow = c.inside ? depth : -depth;
  auto offset_radius = [&](Real radius) { return std::max(0.5 * radius, radius + grow); };
  switch (c.shape.type) {
    case ShapeType::box: {
      const Vec3 half = c.shape.half_extents.unaryExpr(offset_radius);
      std::vector<Vec3> points = box_surface(half, spacing);
      for (Vec3& p : points) p = c.rotation * p;
      return points;
    }
    case ShapeType::sphere: {
      const Real radius = offset_radius(c.shape.radius);
      const int count = std::max(12, static_cast<int>(std::ceil(4 * kPi * radius * radius / (spacing * spacing))));
      std::vector<Vec3> points = fibonacci_sphere(count);
      for (Vec3& p : points) p *= radius;
      return points;
    }
    case ShapeType::capsule: {
      // Cylinder along local y, then two hemispherical caps.
      const Real radius = offset_radius(c.shape.radius);
      std::vector<Vec3> points;
      const int around = std::max(8, static_cast<int>(std::ceil(2 * kPi * radius / spacing)));
      const int along = std::max(1, static_cast<int>(std::ceil(2 * c.shape.half_height / spacing)));
      for (int a = 0; a <= along; ++a)
        for (int k = 0; k < around; ++k) {
          const Real phi = 2 * kPi * k / around;
          points.push_back(c.rotation *
                           Vec3(radius * std::cos(phi), -c.shape.half_height + 2 * c.shape.half_height * a / along, radius * std::sin(phi)));
        }
      const int cap = std::max(12, static_cast<int>(std::ceil(4 * kPi * radius * radius / (spacing * spacing))));
      for (const Vec3& u : fibonacci_sphere(cap)) {
        if (std::abs(u.y()) < 1e-12) continue;
        const Vec3 local = radius * u + Vec3(0, u.y() > 0 ? c.shape.half_height : -c.shape.half_height, 0);
        points.push_back(c.rotation * local);
      }
      return points;
    }
    case ShapeType::plane: {
      // A square patch parallel to the plane, `depth` behind it, around the projection of plane_center.
      const Vec3 n = c.normal;
      const Vec3 t1 = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
      const Vec3 t2 = n.cross(t1);
      const Vec3 origin = plane_center - n.dot(plane_center - c.position) * n - c.position - depth * n;
      const int m = std::max(1, static_cast<int>(std::ceil(2 * plane_half_size / spacing)));
      std::vector<Vec3> points;
      for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= m; ++j)
          points.push_back(origin + (-plane_half_size + 2 * plane_half_size * i / m) * t1 +
                           (-plane_half_size + 2 * plane_half_size * j / m) * t2);
      return points;
    }
    default: unsupported_collider_shape(c.shape.type);
  }
}

double collider_surface_sample_count(const Collider& c, Real spacing, Real depth, Real plane_half_size) {
  const Real grow = c.inside ? depth : -depth;
  auto offset_radius = [&](Real radius) { return std::max(0.5 * radius, radius + grow); };
  auto cells = [spacing](Real length) { return std::max(1.0, std::ceil(length / spacing)); };
  const auto sphere_points = [&](Real radius) { return std::max(12.0, std::ceil(4 * kPi * radius * radius / (spacing * spacing))); };
  switch (c.shape.type) {
    case ShapeType::box: {
      const Vec3 half = c.shape.half_extents.unaryExpr(offset_radius);
      const double n0 = cells(2 * half.x()), n1 = cells(2 * half.y()), n2 = cells(2 * half.z());
      return (n0 + 1) * (n1 + 1) * (n2 + 1) - std::max(0.0, n0 - 1) * std::max(0.0, n1 - 1) * std::max(0.0, n2 - 1);
    }
    case ShapeType::sphere: return sphere_points(offset_radius(c.shape.radius));
    case ShapeType::capsule: {
      const Real radius = offset_radius(c.shape.radius);
      return (cells(2 * c.shape.half_height) + 1) * std::max(8.0, std::ceil(2 * kPi * radius / spacing)) + sphere_points(radius);
    }
    case ShapeType::plane: {
      const double m = cells(2 * plane_half_size);
      return (m + 1) * (m + 1);
    }
    default: unsupported_collider_shape(c.shape.type);
  }
}

std::vector<Real> akinci_volumes(const std::vector<Vec3>& world, Real spacing, const CubicSplineKernel& kernel) {
  // S_flat: the sum over a flat square layer at the fluid spacing (the sample itself included).
  Real flat_sum = 0;
  const int reach = static_cast<int>(std::ceil(kernel.h / spacing));
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b) flat_sum += kernel.value(spacing * std::hypot(a, b));
  const Real fluid_volume = spacing * spacing * spacing;
  NeighborSearch search;
  search.build(world, kernel.h);
  std::vector<Real> volume(world.size());
  for (Index b = 0; b < static_cast<Index>(world.size()); ++b) {
    Real sum = kernel.value(0);
    for (Index k = 0; k < search.count(b); ++k) sum += kernel.value((world[b] - world[search.neighbors(b)[k]]).norm());
    volume[b] = fluid_volume * flat_sum / sum;
  }
  return volume;
}

FluidBoundarySamples sample_fluid_walls(const std::vector<Collider>& colliders, const std::vector<Index>& sampled,
                                        Real spacing, const CubicSplineKernel& kernel, const Vec3& plane_center,
                                        Real plane_half_size) {
  FluidBoundarySamples samples;
  std::vector<Vec3> world;
  for (Index c : sampled) {
    const Collider& collider = colliders[c];
    for (const Vec3& p : sample_collider_surface(collider, spacing, 0.5 * spacing, plane_center, plane_half_size)) {
      samples.local_position.push_back(p);
      samples.collider.push_back(c);
      world.push_back(collider.position + p);
    }
    samples.moving |= collider.velocity.squaredNorm() > 0;
  }
  // Volumes over all samples together, so walls that meet count each other.
  samples.volume = akinci_volumes(world, spacing, kernel);
  return samples;
}

}  // namespace moreau
