#pragma once
// The regions a granular object or a continuum fills (FilledRegions), walked in one order for
// both: each region is checked, then hands its bounding box and a test for the lattice points it
// keeps to the object's own lattice.
#include <fmt/format.h>

#include <string>

#include "moreau/geometry/point_in_mesh.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

/// What a lattice point of the object stands for.
struct LatticeParticle {
  Real size;         // m: the least extent of a region that holds one (a grain's diameter, a cell's edge)
  Real inset;        // m: how far inside a cylinder's or sphere's surface a kept point lies (a grain's radius)
  std::string what;  // the size's name in errors: "grain diameter", "particle spacing"
};

/// Calls fill(region_place, field, lo, hi, keep) for the blocks, then the cylinders, the spheres
/// and the mesh, in that order: lo, hi the region's bounding box and keep(x) whether lattice point
/// x belongs to it; field is the key an error about what the region holds names. `count()` gives
/// the points filled so far, so that a mesh holding none of them is refused.
template <class Fill, class Count>
void fill_regions(const FilledRegions& regions, const SpecPlace& place, const SceneBuildContext& ctx,
                  const LatticeParticle& particle, Fill fill, Count count) {
  const Real size = particle.size * (1 - 1e-9);  // a region exactly one particle across holds it
  auto too_small = [&](const SpecPlace& at, const char* field, const char* shape, const char* extent) {
    at.fail(field,
            fmt::format("the {} must be at least one {} ({} m) {}", shape, particle.what, particle.size, extent));
  };
  for (size_t b = 0; b < regions.blocks.size(); ++b) {
    const SpecPlace block = place.at(fmt::format("blocks[{}]", b));
    const Vec3 lo = block.vector("min", regions.blocks[b].min), hi = block.vector("max", regions.blocks[b].max);
    if ((hi.array() - lo.array() < size).any()) too_small(block, "max", "block", "across in every direction");
    fill(block, "max", lo, hi, [](const Vec3&) { return true; });
  }
  for (size_t c = 0; c < regions.cylinders.size(); ++c) {
    const SpecPlace cylinder = place.at(fmt::format("cylinders[{}]", c));
    const Vec3 base = cylinder.vector("base", regions.cylinders[c].base);
    const Real radius = cylinder.number("radius", regions.cylinders[c].radius, Range::positive());
    const Real height = cylinder.number("height", regions.cylinders[c].height, Range::positive());
    if (radius < size / 2) too_small(cylinder, "radius", "cylinder", "wide");
    if (height < size) too_small(cylinder, "height", "cylinder", "tall");
    const Real reach = radius - particle.inset;  // of a kept point from the axis
    fill(cylinder, "radius", base - Vec3(radius, 0, radius), base + Vec3(radius, height, radius), [&](const Vec3& x) {
      return Vec2(x.x() - base.x(), x.z() - base.z()).squaredNorm() <= reach * reach * (1 + 1e-12);
    });
  }
  for (size_t s = 0; s < regions.spheres.size(); ++s) {
    const SpecPlace sphere = place.at(fmt::format("spheres[{}]", s));
    const Vec3 center = sphere.vector("center", regions.spheres[s].center);
    const Real radius = sphere.number("radius", regions.spheres[s].radius, Range::positive());
    if (radius < size / 2) too_small(sphere, "radius", "sphere", "wide");
    const Real reach = radius - particle.inset;  // of a kept point from the centre
    fill(sphere, "radius", center - Vec3::Constant(radius), center + Vec3::Constant(radius),
         [&](const Vec3& x) { return (x - center).squaredNorm() <= reach * reach * (1 + 1e-12); });
  }
  if (!regions.mesh.empty()) {
    const ClosedSurface surface = read_closed_surface(ctx, place, "mesh", regions.mesh);
    const auto before = count();
    fill(place, "mesh", surface.lo, surface.hi, [&](const Vec3& x) { return point_in_closed_mesh(surface.mesh, x); });
    if (count() == before)
      place.fail("mesh", fmt::format("the surface holds none of the lattice's points ({} {} m)", particle.what,
                                     particle.size));
  }
}

}  // namespace moreau
