#pragma once
// Views of an engine's storage as World state arrays (world.hpp): vectors of fixed-size Eigen
// items (Vec3, Quat) or of doubles, seen as item-major doubles without a copy.
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {

/// The first `count` items of `items`, each Item being `sizeof(Item) / sizeof(double)` doubles
/// (Eigen's fixed-size vectors and quaternions hold exactly their coefficients; a quaternion's
/// are x, y, z, w).
template <class Item>
StateArray state_array(std::string name, std::string unit, std::vector<Item>& items, long count, bool writable) {
  static_assert(sizeof(Item) % sizeof(double) == 0, "an item must be made of doubles");
  constexpr int components = sizeof(Item) / sizeof(double);
  return {std::move(name), std::move(unit), components, count,
          std::span<double>(reinterpret_cast<double*>(items.data()), static_cast<size_t>(count) * components), writable};
}

/// `count` items of `components` doubles at `values`.
inline StateArray state_array(std::string name, std::string unit, double* values, int components, long count,
                              bool writable) {
  return {std::move(name), std::move(unit), components, count,
          std::span<double>(values, static_cast<size_t>(count) * components), writable};
}

}  // namespace moreau
