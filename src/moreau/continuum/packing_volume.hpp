#pragma once
// The volume a continuum particle's packing implies, against the volume its deformation gradient
// holds.
//
// F follows the kernel-averaged velocity gradient (velocity_gradient.hpp), which is exact for
// linear motions and blind to particles slipping into the gaps between their neighbours: such
// non-affine motions leave grad v, and so det F, unchanged while the particles pack closer. Under
// sustained flow the packing drifts from det F: plasticine pushed by a piston through a mould
// (scenes/plasticine_mould.json) packed 20 % closer than its mean det F of 0.97 said, and the
// elastic stress, which sees only F, never pushed back; an elastic cube pressed by 29 % strayed
// 7 mm on average from the affine map that frictionless plates impose (0.5 mm with the correction
// below).
//
// The particles' packing is measured as in SPH by the kernel sum n_p = sum_b V_b^0 W(|x_b - x_p|)
// (p itself included) against its value for an interior particle of the undeformed lattice,
// n_lattice = sum_k r^3 W(|k| r) over the cubic lattice of spacing r. For an affinely deformed
// lattice n_lattice / n_p follows det F closely (sheared by 0.5: 0.2 %; stretched 1.2 : 1 / 1.2:
// 1.6 %; compressed to 0.9: 0.4 %), while at a free surface, where the kernel is cut off, the
// sum falls short and the ratio lies above it. The sum is a coarse measure of a strongly deformed
// lattice, though: stretched isochorically 1.3 : 1 it says 3.8 % less volume, 1.5 : 1 11 %, and a
// von Mises block pressed by 22 % sprang back twice as far when det F followed it exactly. So F
// follows the packing only beyond kPackingTolerance: it bounds the drift instead of removing it.
#include <cmath>

#include "moreau/continuum/wendland_kernel.hpp"

namespace moreau {

/// How much closer than det F says the particles may pack before F follows them.
constexpr Real kPackingTolerance = 0.1;

/// n_lattice: sum over the cubic lattice points k r (|k| r inside the support) of r^3 W(|k| r).
inline Real lattice_kernel_sum(const WendlandKernel& kernel, Real spacing) {
  const int reach = static_cast<int>(kernel.h / spacing) + 1;
  Real sum = 0;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      for (int k = -reach; k <= reach; ++k) sum += kernel.value(spacing * std::sqrt(Real(i * i + j * j + k * k)));
  return sum * spacing * spacing * spacing;
}

/// The elastic deformation gradient with its volume brought down to what the particles' packing
/// implies, when they pack closer than it holds by more than `tolerance`: with J_packing =
/// n_lattice / n_p and the plastic volume ratio J_p (snow's compaction; 1 for the other models)
/// the elastic volume the packing allows is J_packing / (J_p (1 - tolerance)); if det F is above
/// it, F is scaled by the cube root of their ratio, which keeps its shape and rotation. Packings
/// looser than F (free surfaces, sand torn apart) leave F alone: a continuum that tore open is not
/// pulled back by it.
inline Mat3 packed_deformation(const Mat3& F, Real packing_volume, Real plastic_volume,
                               Real tolerance = kPackingTolerance) {
  const Real J = F.determinant(), target = packing_volume / (plastic_volume * (1 - tolerance));
  if (!(J > target) || !(target > 0)) return F;
  return std::cbrt(target / J) * F;
}

}  // namespace moreau
