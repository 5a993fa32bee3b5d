#include "moreau/constraints/suction_cavity.hpp"

#include <algorithm>

namespace moreau {

CavityVolume cavity_volume(const SuctionCup& cup, const Vec3* x, const Vec3& o, const Vec3& n, const Vec3& center) {
  CavityVolume out;
  out.gradient.assign(cup.cavity_vertices.size(), Vec3::Zero());
  auto slot = [&](Index p) {
    return std::lower_bound(cup.cavity_vertices.begin(), cup.cavity_vertices.end(), p) - cup.cavity_vertices.begin();
  };
  for (const auto& t : cup.cavity) {
    const Vec3 &x1 = x[t[0]], &x2 = x[t[1]], &x3 = x[t[2]];
    const Real normal_area = 0.5 * n.dot((x2 - x1).cross(x3 - x1));  // n . a_t
    const Real mean_height = (n.dot(x1 - o) + n.dot(x2 - o) + n.dot(x3 - o)) / 3;
    out.volume -= mean_height * normal_area;
    out.area -= normal_area;
    // The plane turning by dtheta about the centre lifts each height by dtheta . (n x (x - c)) and
    // tilts n by dtheta x n, which changes n . a_t by (dtheta x n) . a_t = dtheta . (n x a_t).
    const Vec3 a_t = 0.5 * (x2 - x1).cross(x3 - x1);
    out.surface_turn -= normal_area * n.cross((x1 + x2 + x3) / 3 - center) + mean_height * n.cross(a_t);
    const Vec3 shared = n * (normal_area / 3);
    out.gradient[slot(t[0])] -= shared + 0.5 * mean_height * (x2 - x3).cross(n);
    out.gradient[slot(t[1])] -= shared + 0.5 * mean_height * (x3 - x1).cross(n);
    out.gradient[slot(t[2])] -= shared + 0.5 * mean_height * (x1 - x2).cross(n);
  }
  return out;
}

}  // namespace moreau
