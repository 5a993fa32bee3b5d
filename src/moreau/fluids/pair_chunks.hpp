#pragma once
// Neighbour pairs in chunks of eight, laid out so the compiler can vectorise the kernel (SIMD
// across neighbours). The pair loops of the fluid are bound by one square root and one division
// per pair; evaluated lane by lane over a chunk they run 4 (AVX2) or 2 (SSE2) at a time.
// Per-lane partial sums are added in a fixed order at the end, so a particle's result does not
// depend on the thread count (it may differ in the last bits between machines whose instruction
// sets differ: the AVX2 clone contracts a*b+c into fused multiply-adds).
//
// Unused lanes of the last chunk get the offset (2h, 0, 0), where every kernel value is zero.
#include "moreau/fluids/sph_kernel.hpp"

namespace moreau {

inline constexpr int kPairChunk = 8;

struct PairChunk {
  alignas(64) Real rx[kPairChunk], ry[kPairChunk], rz[kPairChunk];  // x_i - x_j, m
  alignas(64) Real w[kPairChunk], g[kPairChunk];                     // W(r), (dW/dr)/r
  alignas(64) Real a[kPairChunk], b[kPairChunk];                     // per-neighbour values (0 in pad lanes)

  /// Loads neighbours row[begin, begin + kPairChunk) (clipped at `end`) of the point xi, and
  /// a[k] = values_a[j], b[k] = values_b[j] when those are given. `pad` = 2h.
  void load(const Vec3& xi, const Vec3* x, const Index* row, Index begin, Index end, Real pad,
            const Real* values_a = nullptr, const Real* values_b = nullptr) {
    const int size = static_cast<int>(std::min<Index>(kPairChunk, end - begin));
    for (int k = 0; k < kPairChunk; ++k) {
      if (k < size) {
        const Index n = row[begin + k];
        const Vec3& xj = x[n];
        rx[k] = xi.x() - xj.x();
        ry[k] = xi.y() - xj.y();
        rz[k] = xi.z() - xj.z();
        a[k] = values_a ? values_a[n] : 0;
        b[k] = values_b ? values_b[n] : 0;
      } else {
        rx[k] = pad;
        ry[k] = rz[k] = 0;
        a[k] = b[k] = 0;
      }
    }
  }

  /// w and g of every lane: the cubic spline of sph_kernel.hpp in branch-free form, with
  /// a = max(1 - q, 0), b = max(1/2 - q, 0):
  ///   W = sigma (2 a^3 - 8 b^3),   (dW/dr) / r = sigma / h (24 b^2 - 6 a^2) / r
  /// (zero for q >= 1 without a test, so pad lanes and list entries in the skin cost no branch).
  void evaluate(const CubicSplineKernel& kernel) {
    const Real sigma = kernel.sigma, inv_h = kernel.inv_h, floor2 = 1e-12 * kernel.h2;
    #pragma omp simd
    for (int k = 0; k < kPairChunk; ++k) {
      // No branches, so the loop vectorises: max(x, 0) = (x + |x|) / 2 exactly, and r is taken as
      // sqrt(r^2 + 1e-12 h^2) (relative change below 1e-11 for any pair in the support).
      const Real r = std::sqrt(rx[k] * rx[k] + ry[k] * ry[k] + rz[k] * rz[k] + floor2);
      const Real q = r * inv_h;
      const Real a = 0.5 * ((1 - q) + std::abs(1 - q)), b = 0.5 * ((0.5 - q) + std::abs(0.5 - q));
      w[k] = sigma * (2 * a * a * a - 8 * b * b * b);
      g[k] = sigma * inv_h * (24 * b * b - 6 * a * a) / r;
    }
  }
};

/// Adds the lanes of a per-lane sum in a fixed order.
inline Real sum_lanes(const Real* lanes) {
  Real s = 0;
  for (int k = 0; k < kPairChunk; ++k) s += lanes[k];
  return s;
}

}  // namespace moreau
