#include "moreau/solvers/nmd/turning_contact_rows.hpp"

namespace moreau {

bool add_turning_rows(NmdBlockInput& in, const VelocitySpace& space, const std::array<TurningSide, 2>& sides,
                      const Vec3& n, const Vec3& t1, const Vec3& t2, Real rolling) {
  const int spins = (sides[0].grain >= 0) + (sides[1].grain >= 0);
  if (spins == 0) return false;
  const int first_spin = in.ends();
  in.extend(6, first_spin + spins);
  const std::array<Vec3, 3> contact_direction{n, t1, t2};  // rows 0, 1, 2
  const std::array<Vec3, 3> turning_direction{t1, t2, n};  // rows 3, 4, 5
  auto set = [](Real* entries, const Vec3& value) {
    for (int c = 0; c < 3; ++c) entries[c] = value[c];
  };
  int e = first_spin;
  for (int k = 0; k < 2; ++k) {
    const TurningSide& side = sides[k];
    const Real sign = k == 0 ? 1 : -1;
    if (side.grain >= 0) {
      in.end[e] = space.spin_end(side.grain);
      const Vec3 arm = -sign * side.arm * n;  // a_i = -r_i n, a_j = +r_j n
      for (int r = 1; r < 3; ++r) set(in.at(r, e), sign * arm.cross(contact_direction[r]));  // the normal row's: a x n = 0
      for (int r = 0; r < 3; ++r) set(in.at(3 + r, e), sign * turning_direction[r]);
      ++e;
    } else if (side.body_end >= 0) {
      for (int r = 0; r < 3; ++r) set(in.at(3 + r, side.body_end) + 3, sign * turning_direction[r]);
    }
  }
  for (int r = 3; r < 6; ++r) in.level[r] = RowLevel::friction;
  in.rolling = rolling;
  return true;
}

void make_grain_pair(NmdBlockInput& in, const Vec3& n, const Vec3& t1, const Vec3& t2, Real arm_i, Real arm_j,
                     Real rolling) {
  in.kind = NmdBlockKind::grain_pair;
  for (int r = 3; r < 6; ++r) in.level[r] = RowLevel::friction;
  in.rolling = rolling;
  in.grain_pair.n = n;
  in.grain_pair.t1 = t1;
  in.grain_pair.t2 = t2;
  in.grain_pair.arm[0] = arm_i;
  in.grain_pair.arm[1] = arm_j;
}

}  // namespace moreau
