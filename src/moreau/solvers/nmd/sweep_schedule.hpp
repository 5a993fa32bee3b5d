#pragma once
// The order in which a Gauss-Seidel sweep visits the blocks of an NMD system, arranged so that
// threads can share a sweep and still produce the serial sweep's result bit for bit.
//
// Consecutive blocks over the same ends (the points of one contact manifold, say) form a task,
// solved by one thread in assembly order. Tasks are placed in levels: a task's level is one more
// than the highest level of any earlier task that moves one of its ends (the world, fixed and
// kinematic bodies and pinned particles move nothing and never conflict). Within a level no two
// tasks touch the same moving velocity, so they commute; across levels every pair of tasks that
// shares a velocity keeps its assembly order. Sweeping level by level is therefore the same
// sequence of floating-point operations on every velocity and impulse as sweeping the blocks in
// assembly order, whatever the number of threads and however a level is split between them.
// (A greedy colouring would need fewer levels but would reorder the sweep, and its result would
// then differ from the serial one.)
#include <vector>

#include "moreau/solvers/nmd/nmd_system.hpp"

namespace moreau {

struct SweepSchedule {
  std::vector<Index> task_block;   // first block of each task, in sweep order
  std::vector<Index> task_end;     // one past the last block of each task (same order)
  std::vector<Index> level_first;  // first task of each level; then the task count

  Index levels() const { return static_cast<Index>(level_first.size()) - 1; }
  Index tasks() const { return static_cast<Index>(task_end.size()); }

  /// Arranges the blocks of `system` (velocity vector of `dof_count` entries).
  void build(const NmdSystem& system, Index dof_count);

 private:
  std::vector<int> next_level_;    // per velocity entry: the lowest level a new task moving it may take
  std::vector<int> task_level_;    // per task in assembly order
  std::vector<Index> first_, end_; // per task in assembly order: its blocks
  std::vector<Index> first_scratch_;  // the next free place of each level while sorting
};

}  // namespace moreau
