#pragma once
// Joints of the FEM engine: constraints between director rigid bodies, solid nodes and the world,
// held at the end of every step and solved in one Newton system with the solids and the bodies
// (coupled_step.hpp). Every joint row is linear or quadratic in the unknowns q = (u, phi, d), so
// with its force G(q_{n+1/2})^T lambda the joint does no work over a step
// (G(q_{n+1/2}) (q1 - q0) = g(q1) - g(q0) = 0) and energy and momentum stay conserved.
//   spherical  p_a - p_b = 0 (3 rows), a point of each end: a body's material point
//              phi + sum_i c_i d_i (c_i its coordinates along the reference directors), a solid
//              node X + u, or a fixed world point
//   hinge      spherical, plus n_a . e_b1 = 0 and n_a . e_b2 = 0 for the hinge axis n_a fixed in
//              end a and two directions e_b1, e_b2 normal to it fixed in end b (bodies or the
//              world); a hinge to a solid holds every solid node on the hinge axis
//              (spherical rows each), which leaves the rotation about the axis free
// (Betsch & Steinmann 2001, sec. 5: joints as external constraints on q.)
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

enum class FemJointEndKind { world, body, node };

struct FemJointEnd {
  FemJointEndKind kind = FemJointEndKind::world;
  Index index = -1;              // body or global node
  Vec3 coordinates = Vec3::Zero();  // body: c_i along its reference directors; world: the point
};

/// One vector-valued row group p_a - p_b = 0 (spherical rows), or a scalar row n_a . e_b = 0.
struct FemJointRows {
  enum class Kind { coincide, perpendicular } kind = Kind::coincide;
  FemJointEnd a, b;
  // perpendicular: direction of end a and of end b, each as coordinates along its reference
  // directors (bodies) or a world vector.
  Vec3 direction_a = Vec3::Zero(), direction_b = Vec3::Zero();
};

struct FemJoint {
  std::string name;
  std::vector<FemJointRows> rows;
  int row_count() const {
    int n = 0;
    for (const auto& r : rows) n += r.kind == FemJointRows::Kind::coincide ? 3 : 1;
    return n;
  }
};

}  // namespace moreau
