// The shared fixed-radius neighbour search against brute force, and its independence of the
// thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "moreau/geometry/neighbor_search.hpp"

using namespace moreau;

namespace {

std::vector<Vec3> random_cloud(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(-1, 1);
  std::vector<Vec3> x(n);
  for (auto& p : x) p = Vec3(u(rng), 0.5 * u(rng), 2 * u(rng));
  return x;
}

}  // namespace

TEST(NeighborSearch, MortonKeyInterleavesBits) {
  EXPECT_EQ(CellGrid::morton_key(1, 0, 0), 1u);
  EXPECT_EQ(CellGrid::morton_key(0, 1, 0), 2u);
  EXPECT_EQ(CellGrid::morton_key(0, 0, 1), 4u);
  EXPECT_EQ(CellGrid::morton_key(3, 0, 0), 9u);  // bits 0 and 3
  EXPECT_EQ(CellGrid::morton_key((1u << 21) - 1, 0, 0), 0x1249249249249249ULL);
}

TEST(NeighborSearch, FindsExactlyThePairsBruteForceFinds) {
  // Random points plus a lattice of spacing h/3 (pairs at exactly the radius) and a duplicate.
  std::vector<Vec3> x = random_cloud(3000, 7);
  const Real radius = 0.15;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) x.emplace_back(0.05 * i, 0.05 * j, 0.0);
  x.push_back(x[10]);
  NeighborSearch search;
  search.build(x, radius, 1);
  long pairs = 0;
  for (Index i = 0; i < static_cast<Index>(x.size()); ++i) {
    std::vector<Index> expected;
    for (Index j = 0; j < static_cast<Index>(x.size()); ++j)
      if (j != i && (x[i] - x[j]).squaredNorm() < radius * radius) expected.push_back(j);
    std::vector<Index> found(search.neighbors(i), search.neighbors(i) + search.count(i));
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, expected) << "point " << i;
    pairs += found.size();
  }
  EXPECT_EQ(search.total(), pairs);
  EXPECT_GT(pairs, 10000);  // the test is not vacuous
  // order() is a permutation.
  std::vector<Index> order = search.order();
  std::sort(order.begin(), order.end());
  for (Index k = 0; k < static_cast<Index>(order.size()); ++k) ASSERT_EQ(order[k], k);
}

TEST(NeighborSearch, ListsAreIdenticalForOneAndTwoThreads) {
  const std::vector<Vec3> x = random_cloud(20000, 3);
  NeighborSearch one, two;
  one.build(x, 0.08, 1);
  two.build(x, 0.08, 2);
  ASSERT_EQ(one.total(), two.total());
  for (Index i = 0; i < static_cast<Index>(x.size()); ++i) {
    ASSERT_EQ(one.count(i), two.count(i));
    ASSERT_TRUE(std::equal(one.neighbors(i), one.neighbors(i) + one.count(i), two.neighbors(i))) << i;
  }
  // Rebuilding with the same buffers (warm) gives the same lists.
  one.build(x, 0.08, 2);
  for (Index i = 0; i < static_cast<Index>(x.size()); ++i)
    ASSERT_TRUE(std::equal(one.neighbors(i), one.neighbors(i) + one.count(i), two.neighbors(i))) << i;
}
