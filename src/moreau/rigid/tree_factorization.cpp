#include "moreau/rigid/tree_factorization.hpp"

#include "moreau/rigid/joint_tree.hpp"

namespace moreau {

void TreeFactorization::factor(const JointForest& forest, std::vector<TreeBlock>& diagonal,
                               const std::vector<TreeBlock>& coupling) {
  forest_ = &forest;
  factor_.resize(forest.nodes.size());
  to_parent_.resize(forest.nodes.size());
  // Leaves first: D_i -> LDL^T, J_i = D_i^-1 H_i,parent, D_parent -= H_i,parent^T J_i.
  for (size_t i = 0; i < forest.nodes.size(); ++i) {
    factor_[i].compute(diagonal[i]);
    const Index p = forest.nodes[i].parent;
    if (p < 0) continue;
    to_parent_[i] = factor_[i].solve(coupling[i]);
    diagonal[p] -= coupling[i].transpose() * to_parent_[i];
  }
}

void TreeFactorization::solve(std::vector<TreeColumn>& s) const {
  const JointForest& forest = *forest_;
  const size_t n = forest.nodes.size();
  for (size_t i = 0; i < n; ++i)
    if (const Index p = forest.nodes[i].parent; p >= 0) s[p] -= to_parent_[i].transpose() * s[i];
  for (size_t i = n; i-- > 0;) {
    s[i] = factor_[i].solve(s[i]);
    if (const Index p = forest.nodes[i].parent; p >= 0) s[i] -= to_parent_[i] * s[p];
  }
}

}  // namespace moreau
