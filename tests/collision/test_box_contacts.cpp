// The closed-form box-box separating-axis test against the generic polyhedron test.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "moreau/collision/narrow_phase_parts.hpp"
#include "moreau/collision/shape.hpp"

namespace moreau {
namespace {

// The closed-form box test (box_contacts.cpp) must pick the axes the generic polyhedron test
// picks and build the same contacts: 2000 random pairs of boxes of random sizes, near enough to
// touch (faces, edges and corners in every orientation), compared point by point. Tolerance 1e-12 m:
// the two compute each axis's separation in a different order of roundings.
TEST(NarrowPhase, BoxPairsInClosedFormMatchTheGenericPolyhedronTest) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> unit(-1, 1), size(0.05, 0.6);
  auto random_pose = [&](Real spread) {
    const Quat q = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
    return Pose{Vec3(spread * unit(rng), spread * unit(rng), spread * unit(rng)), q};
  };
  int touching = 0, edges = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Shape a = make_box(Vec3(size(rng), size(rng), size(rng)));
    const Shape b = make_box(Vec3(size(rng), size(rng), size(rng)));
    const Pose pa = random_pose(0.2), pb = random_pose(0.8);
    const Real margin = 0.02;
    narrow::Candidates closed, generic;
    narrow::collide_boxes(a, pa, b, pb, margin, closed);
    narrow::collide_polyhedra(a, pa, b, pb, margin, generic);
    const ContactManifold m = narrow::reduce_to_manifold(closed, pa, pb), g = narrow::reduce_to_manifold(generic, pa, pb);
    ASSERT_EQ(m.count, g.count) << "trial " << trial;
    touching += m.count > 0;
    edges += m.count == 1;
    for (int k = 0; k < m.count; ++k) {
      EXPECT_LT((m.points[k].core_a - g.points[k].core_a).norm(), 1e-12) << "trial " << trial;
      EXPECT_LT((m.points[k].core_b - g.points[k].core_b).norm(), 1e-12) << "trial " << trial;
      EXPECT_LT((m.points[k].normal - g.points[k].normal).norm(), 1e-12) << "trial " << trial;
    }
  }
  // The sample must exercise both kinds of contact (measured: 1124 within the margin, 598 single points).
  std::printf("box pairs: %d of 2000 within the margin, %d of them single edge or corner points\n", touching, edges);
  EXPECT_GT(touching, 500);
  EXPECT_GT(edges, 50);
}

}  // namespace
}  // namespace moreau
