#pragma once
// An admissible interval for a number of a scene, and how it reads in a message.
#include <string>

#include "moreau/math/types.hpp"

namespace moreau {

/// An admissible interval for a number; open ends exclude the bound.
struct Range {
  Real lo = -1e300, hi = 1e300;
  bool lo_open = false, hi_open = false;
  static Range any() { return {}; }
  static Range positive() { return {0, 1e300, true, false}; }
  static Range non_negative() { return {0, 1e300, false, false}; }
  static Range closed(Real a, Real b) { return {a, b, false, false}; }
  static Range open(Real a, Real b) { return {a, b, true, true}; }
  bool contains(Real v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  /// "> 0", "[0, 1]", "any number", ...
  std::string describe() const;
};

}  // namespace moreau
