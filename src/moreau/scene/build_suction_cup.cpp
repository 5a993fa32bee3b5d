// "suction" of a soft body: which boundary faces roof its cavity and which vertices seal it.
#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "moreau/scene/spec_builders.hpp"

namespace moreau {

void add_suction_cup(const SuctionSpec& spec, const SpecPlace& place, const std::vector<Vec3>& rest,
                     const std::vector<std::array<Index, 3>>& boundary, Index base, Index object, Model& model) {
  const Vec3 opening = place.vector("opening", spec.opening);
  if (!(opening.norm() > 0)) place.fail("opening", "must be a nonzero direction (the way the cup's mouth faces)");
  const Vec3 o = opening.normalized();
  SuctionCup cup;
  cup.object = object;
  cup.atmospheric_pressure = place.number("atmospheric_pressure", spec.atmospheric_pressure, Range::positive());
  cup.seal_gap = place.number("seal_gap", spec.seal_gap, Range::non_negative());

  // The mouth is the plane furthest along the opening; its faces (the rim's flat underside) touch
  // the surface and enclose nothing.
  Real mouth = -std::numeric_limits<Real>::infinity(), lowest = std::numeric_limits<Real>::infinity();
  for (const Vec3& x : rest) {
    mouth = std::max(mouth, x.dot(o));
    lowest = std::min(lowest, x.dot(o));
  }
  const Real tolerance = 1e-4 * (mouth - lowest);
  auto in_mouth = [&](Index v) { return rest[v].dot(o) >= mouth - tolerance; };

  std::map<std::pair<Index, Index>, int> edge_count;
  for (const auto& f : boundary) {
    const Vec3 normal = (rest[f[1]] - rest[f[0]]).cross(rest[f[2]] - rest[f[0]]);
    if (!(normal.dot(o) > 1e-3 * normal.norm())) continue;
    if (in_mouth(f[0]) && in_mouth(f[1]) && in_mouth(f[2])) continue;
    cup.cavity.push_back({base + f[0], base + f[1], base + f[2]});
    for (int k = 0; k < 3; ++k) {
      const Index a = f[k], b = f[(k + 1) % 3];
      ++edge_count[{std::min(a, b), std::max(a, b)}];
    }
  }
  if (cup.cavity.empty())
    place.fail("opening", "no boundary face of the soft body looks along it off the mouth: the mesh has no cavity there");
  for (const auto& [edge, count] : edge_count) {
    if (count != 1) continue;
    for (Index v : {edge.first, edge.second}) {
      if (!in_mouth(v))
        place.fail("opening", fmt::format("the cavity's edge leaves the mouth at vertex {} ({:.4g} m short of it): the faces "
                                          "looking along the opening must meet the mouth's plane in a closed rim",
                                          v, mouth - rest[v].dot(o)));
      cup.rim.push_back(base + v);
    }
  }
  if (cup.rim.empty()) place.fail("opening", "the faces looking along it close on themselves: the cavity has no rim");
  std::sort(cup.rim.begin(), cup.rim.end());
  cup.rim.erase(std::unique(cup.rim.begin(), cup.rim.end()), cup.rim.end());
  for (const auto& f : cup.cavity) cup.cavity_vertices.insert(cup.cavity_vertices.end(), f.begin(), f.end());
  std::sort(cup.cavity_vertices.begin(), cup.cavity_vertices.end());
  cup.cavity_vertices.erase(std::unique(cup.cavity_vertices.begin(), cup.cavity_vertices.end()), cup.cavity_vertices.end());
  model.suction_cups.push_back(std::move(cup));
}

}  // namespace moreau
