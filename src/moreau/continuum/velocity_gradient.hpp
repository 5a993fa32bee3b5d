#pragma once
// The kernel-corrected velocity gradient of a particle continuum (XPBI, Yu et al. 2024, after
// Bonet and Lok 1999's corrected kernel gradients). With g_b = grad_{x_p} W(|x_p - x_b|) and the
// neighbours' volumes V_b,
//   M_p = sum_b V_b g_b (x_b - x_p)^T,   L_p = M_p^-1,
//   grad v_p = sum_b V_b (v_b - v_p) (L_p g_b)^T,
// which is exact for every linear velocity field v = A x + c: sum_b V_b A (x_b - x_p) g_b^T L_p^T
// = A (L_p M_p)^T = A. Near a free surface M_p loses rank (a particle with neighbours in a plane
// only sees that plane): L_p is then its pseudo-inverse, singular values below `tolerance` times
// the largest dropped, and the gradient is exact within the directions the neighbours span and
// zero across them.
#include <span>

#include "moreau/continuum/wendland_kernel.hpp"

namespace moreau {

/// One neighbour as the estimates see it: its offset x_b - x_p (m) and volume V_b (m^3).
struct KernelNeighbor {
  Vec3 offset;
  Real volume;
};

/// L_p, the inverse (or pseudo-inverse) of M_p over the particle's neighbours.
Mat3 kernel_correction(const WendlandKernel& kernel, std::span<const KernelNeighbor> neighbors,
                       Real tolerance = 1e-6);

/// The corrected kernel gradient L_p g_b of neighbour b at offset x_b - x_p (1/m^4).
inline Vec3 corrected_gradient(const WendlandKernel& kernel, const Mat3& correction, const Vec3& offset) {
  // g_b = grad_{x_p} W(|x_p - x_b|) = (x_p - x_b) dW/dr / r = -offset * gradient_factor
  return correction * (-kernel.gradient_factor(offset.norm()) * offset);
}

/// grad v_p (1/s) from the neighbours' velocity differences v_b - v_p, in the neighbours' order.
Mat3 velocity_gradient(const WendlandKernel& kernel, const Mat3& correction, std::span<const KernelNeighbor> neighbors,
                       std::span<const Vec3> velocity_difference);

}  // namespace moreau
