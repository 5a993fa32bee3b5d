#include "moreau/solvers/nmd/sweep_schedule.hpp"

#include <algorithm>

namespace moreau {

namespace {

// Whether blocks a and b move the same ends in the same order.
bool same_ends(const NmdSystem& s, const NmdBlock& a, const NmdBlock& b) {
  if (a.ends != b.ends) return false;
  const VelocityEnd* ea = s.ends_of(a);
  const VelocityEnd* eb = s.ends_of(b);
  for (int e = 0; e < a.ends; ++e)
    if (ea[e].dof != eb[e].dof || ea[e].moves != eb[e].moves) return false;
  return true;
}

}  // namespace

void SweepSchedule::build(const NmdSystem& system, Index dof_count) {
  first_.clear();
  end_.clear();
  task_level_.clear();
  next_level_.assign(dof_count, 0);
  const Index block_count = static_cast<Index>(system.blocks.size());
  int levels = 0;
  for (Index b = 0; b < block_count;) {
    Index e = b + 1;
    while (e < block_count && same_ends(system, system.blocks[b], system.blocks[e])) ++e;
    // The task's level: after every earlier task that moves one of its ends. An end's entries
    // are always claimed together, so its first entry stands for all of them.
    const VelocityEnd* end = system.ends_of(system.blocks[b]);
    int level = 0;
    for (int k = 0; k < system.blocks[b].ends; ++k)
      if (end[k].size > 0 && end[k].moves) level = std::max(level, next_level_[end[k].dof]);
    for (int k = 0; k < system.blocks[b].ends; ++k)
      if (end[k].size > 0 && end[k].moves) next_level_[end[k].dof] = level + 1;
    first_.push_back(b);
    end_.push_back(e);
    task_level_.push_back(level);
    levels = std::max(levels, level + 1);
    b = e;
  }
  // Tasks by level, in assembly order within a level (a counting sort).
  level_first.assign(levels + 1, 0);
  for (int level : task_level_) ++level_first[level + 1];
  for (int l = 0; l < levels; ++l) level_first[l + 1] += level_first[l];
  const Index tasks = static_cast<Index>(first_.size());
  task_block.resize(tasks);
  task_end.resize(tasks);
  std::vector<Index>& slot = first_scratch_;
  slot.assign(level_first.begin(), level_first.end() - 1);
  for (Index t = 0; t < tasks; ++t) {
    const Index at = slot[task_level_[t]]++;
    task_block[at] = first_[t];
    task_end[at] = end_[t];
  }
}

}  // namespace moreau
