// The order threads share a Gauss-Seidel sweep in (sweep_schedule.hpp): tasks that move a common
// velocity never share a level and keep their assembly order, so the shared sweep repeats the
// serial one exactly.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "moreau/solvers/nmd/sweep_schedule.hpp"

namespace moreau {
namespace {

// A system of `count` blocks over random pairs of 40 bodies (6 entries each) and the world, some
// immovable, with runs of blocks over the same pair (the points of one contact manifold).
NmdSystem random_blocks(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> body(-1, 39), run(1, 4);
  NmdSystem s;
  while (static_cast<int>(s.blocks.size()) < count) {
    const int a = body(rng), b = body(rng);
    const int points = run(rng);
    for (int p = 0; p < points; ++p) {
      NmdBlock block;
      block.ends = 2;
      block.first_end = static_cast<Index>(s.block_ends.size());
      for (int e : {a, b}) {
        VelocityEnd end;
        if (e >= 0) end = {6 * e, 6, e % 7 != 0};  // every seventh body is fixed: nothing moves it
        s.block_ends.push_back(end);
      }
      s.blocks.push_back(block);
    }
  }
  return s;
}

// Whether blocks i and j move a common velocity.
bool conflict(const NmdSystem& s, Index i, Index j) {
  const VelocityEnd *a = s.ends_of(s.blocks[i]), *b = s.ends_of(s.blocks[j]);
  for (int x = 0; x < s.blocks[i].ends; ++x)
    for (int y = 0; y < s.blocks[j].ends; ++y)
      if (a[x].size > 0 && a[x].moves && b[y].size > 0 && b[y].moves && a[x].dof == b[y].dof) return true;
  return false;
}

TEST(NmdSweepSchedule, ConflictingBlocksKeepTheirOrderAndNeverShareALevel) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const NmdSystem s = random_blocks(300, seed);
    SweepSchedule schedule;
    schedule.build(s, 6 * 40);
    const Index n = static_cast<Index>(s.blocks.size());
    // Every block exactly once; each block's level and position in the sweep.
    std::vector<Index> level(n, -1), position(n, -1), task(n, -1);
    Index visited = 0;
    for (Index l = 0; l < schedule.levels(); ++l)
      for (Index t = schedule.level_first[l]; t < schedule.level_first[l + 1]; ++t) {
        ASSERT_LT(schedule.task_block[t], schedule.task_end[t]);
        for (Index i = schedule.task_block[t]; i < schedule.task_end[t]; ++i) {
          ASSERT_EQ(level[i], -1) << "block " << i << " visited twice";
          level[i] = l;
          task[i] = t;
          position[i] = visited++;
        }
      }
    ASSERT_EQ(visited, n);
    for (Index i = 0; i < n; ++i)
      for (Index j = i + 1; j < n; ++j) {
        if (!conflict(s, i, j)) continue;
        // Within one task (a run over the same ends) blocks go in order on one thread.
        if (task[i] != task[j]) {
          EXPECT_LT(level[i], level[j]) << "seed " << seed << ", blocks " << i << " and " << j;
        }
        EXPECT_LT(position[i], position[j]);
      }
  }
}

TEST(NmdSweepSchedule, IndependentManifoldsShareOneLevel) {
  // 100 bodies each resting on the world with four contact points: one task per body, all in
  // level 0, so a sweep can split them between any number of threads.
  NmdSystem s;
  for (int b = 0; b < 100; ++b)
    for (int p = 0; p < 4; ++p) {
      NmdBlock block;
      block.ends = 2;
      block.first_end = static_cast<Index>(s.block_ends.size());
      s.block_ends.push_back({6 * b, 6, true});
      s.block_ends.push_back({});
      s.blocks.push_back(block);
    }
  SweepSchedule schedule;
  schedule.build(s, 600);
  EXPECT_EQ(schedule.levels(), 1);
  EXPECT_EQ(schedule.tasks(), 100);
}

}  // namespace
}  // namespace moreau
