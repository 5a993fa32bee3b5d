#include "moreau/fluids/density_constraint.hpp"


namespace moreau {

Real fluid_rest_denominator(const CubicSplineKernel& kernel, Real spacing, Real mass) {
  // A particle at the origin of a cubic lattice: D_rest = (V^2 / m) sum_j |grad W_ij|^2 (the sum
  // of the gradients vanishes by symmetry).
  const Real volume = spacing * spacing * spacing;
  const int reach = static_cast<int>(std::ceil(kernel.h / spacing));
  Real sum = 0;
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b)
      for (int c = -reach; c <= reach; ++c) {
        const Vec3 r = spacing * Vec3(a, b, c);
        const Real d = r.norm();
        if (d == 0 || d >= kernel.h) continue;
        sum += (kernel.gradient_factor(d) * r).squaredNorm();
      }
  return volume * volume / mass * sum;
}

}  // namespace moreau
