// The showcase's promise: thin cloth does not pass through the soft block or through itself.
// Checked geometrically on the final state (after the cloth has fallen, draped and settled):
// no cloth vertex lies inside a tetrahedron of the block, and no cloth edge pierces a cloth
// triangle it does not share a vertex with.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_helpers.hpp"

using namespace moreau;

namespace {

bool point_in_tet(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Mat3 T;
  T << b - a, c - a, d - a;
  const Vec3 l = T.inverse() * (p - a);
  return l.minCoeff() > 0 && l.sum() < 1;
}

// Does segment pq cross triangle abc (proper crossing, Moller-Trumbore)?
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 dir = q - p, e1 = b - a, e2 = c - a;
  const Vec3 s = dir.cross(e2);
  const Real det = e1.dot(s);
  if (std::abs(det) < 1e-18) return false;
  const Vec3 t = p - a;
  const Real u = t.dot(s) / det;
  if (u <= 0 || u >= 1) return false;
  const Vec3 r = t.cross(e1);
  const Real v = dir.dot(r) / det;
  if (v <= 0 || u + v >= 1) return false;
  const Real along = e2.dot(r) / det;
  return along > 0 && along < 1;
}

}  // namespace

TEST(ShowcaseContacts, ClothStaysOutsideTheBlockAndDoesNotPierceItself) {
  Scene s = load_scene((std::filesystem::path(MOREAU_SOURCE_DIR) / "scenes" / "showcase.json").string(),
                       {"settings.threads=1"});
  test::run_steps(s, static_cast<long>(std::lround(s.duration / s.model.settings.dt)));
  const Model& m = s.model;
  const auto& x = s.state.position;
  const ObjectInfo& cloth = m.objects[m.find_object("cloth")];
  const ObjectInfo& jelly = m.objects[m.find_object("jelly")];

  int inside = 0;
  for (Index p = cloth.particle_begin; p < cloth.particle_end; ++p)
    for (const auto& t : jelly.tets) inside += point_in_tet(x[p], x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
  EXPECT_EQ(inside, 0) << "cloth vertices inside the block";

  std::vector<std::array<Index, 2>> edges;
  for (const auto& t : cloth.surface)
    for (int k = 0; k < 3; ++k)
      if (t[k] < t[(k + 1) % 3]) edges.push_back({t[k], t[(k + 1) % 3]});
  int crossings = 0;
  for (const auto& tri : cloth.surface) {
    const Vec3 lo = x[tri[0]].cwiseMin(x[tri[1]]).cwiseMin(x[tri[2]]);
    const Vec3 hi = x[tri[0]].cwiseMax(x[tri[1]]).cwiseMax(x[tri[2]]);
    for (const auto& e : edges) {
      if (e[0] == tri[0] || e[0] == tri[1] || e[0] == tri[2] || e[1] == tri[0] || e[1] == tri[1] || e[1] == tri[2])
        continue;
      if ((x[e[0]].cwiseMin(x[e[1]]) - hi).maxCoeff() > 0 || (lo - x[e[0]].cwiseMax(x[e[1]])).maxCoeff() > 0) continue;
      crossings += segment_crosses_triangle(x[e[0]], x[e[1]], x[tri[0]], x[tri[1]], x[tri[2]]);
    }
  }
  EXPECT_EQ(crossings, 0) << "cloth edges piercing cloth triangles";
}
