#pragma once
// The block LDL^T factorisation of a joint forest's matrix (joint_tree.hpp): nodes ordered so that
// every node precedes its parent factor without fill-in,
//   factor   D_i = H_ii - sum_children H_ci^T D_c^-1 H_ci,  J_i = D_i^-1 H_i,parent
//   forward  s_i = b_i - sum_children J_c^T s_c             (leaves to roots)
//   backward s_i = D_i^-1 s_i - J_i s_parent                (roots to leaves)
// Factored once, it solves for as many right-hand sides as asked (the contacts between tree bodies
// need one per row, tree_contacts.hpp).
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "moreau/math/types.hpp"

namespace moreau {

struct JointForest;

// The tree's small blocks (at most 6 x 6; a body node's are 6 x 6 and 6-vectors), stored inline.
using TreeBlock = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using TreeColumn = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, 6, 1>;

class TreeFactorization {
 public:
  /// Factors H: `diagonal` holds H_ii per node (overwritten: the pivots' blocks), `coupling`
  /// H_i,parent for every node with a parent. The storage is kept for the next factorisation.
  void factor(const JointForest& forest, std::vector<TreeBlock>& diagonal, const std::vector<TreeBlock>& coupling);
  /// Solves H s = b in place (`s` holds b, node-indexed, on entry).
  void solve(std::vector<TreeColumn>& s) const;

 private:
  const JointForest* forest_ = nullptr;
  std::vector<Eigen::LDLT<TreeBlock>> factor_;
  std::vector<TreeBlock> to_parent_;
};

}  // namespace moreau
