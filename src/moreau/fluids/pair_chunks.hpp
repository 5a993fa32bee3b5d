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

// A chunk's lanes as one value (GCC vector extensions): the compiler splits it into the widest
// registers the instruction-set clone has.
using Lanes = Real __attribute__((vector_size(kPairChunk * sizeof(Real))));
using LaneMask = long long __attribute__((vector_size(kPairChunk * sizeof(long long))));
static_assert(kPairChunk == 8, "load() and gather() spell out eight lanes");

/// lanes[k] = values[stride * n[k] + offset], k = 0..7, assembled in registers and stored whole.
/// (Vectors are passed by reference: by value their ABI differs between the instruction-set clones.)
[[gnu::always_inline]] inline void gather(Lanes& lanes, const Real* values, const Index* n, int stride, int offset) {
  lanes = Lanes{values[stride * n[0] + offset], values[stride * n[1] + offset], values[stride * n[2] + offset],
                values[stride * n[3] + offset], values[stride * n[4] + offset], values[stride * n[5] + offset],
                values[stride * n[6] + offset], values[stride * n[7] + offset]};
}

/// Stores a vector of lanes into a 64-byte aligned array of kPairChunk values.
[[gnu::always_inline]] inline void store(Real* lanes, const Lanes& value) {
  *reinterpret_cast<Lanes*>(lanes) = value;
}

/// gather() into an aligned array.
[[gnu::always_inline]] inline void gather_into(Real* lanes, const Real* values, const Index* n, int stride,
                                               int offset) {
  Lanes value;
  gather(value, values, n, stride, offset);
  store(lanes, value);
}

struct PairChunk {
  alignas(64) Real rx[kPairChunk], ry[kPairChunk], rz[kPairChunk];  // x_i - x_j, m
  alignas(64) Real w[kPairChunk], g[kPairChunk];                     // W(r), (dW/dr)/r
  alignas(64) Real a[kPairChunk], b[kPairChunk];                     // per-neighbour values (0 in pad lanes)

  /// Loads neighbours row[begin, begin + kPairChunk) (clipped at `end`) of the point xi, and
  /// a[k] = values_a[j], b[k] = values_b[j] when those are given. `pad` = 2h. `row` is a row of
  /// FixedStrideLists, whose last chunk is padded with valid indices.
  [[gnu::always_inline]] void load(const Vec3& xi, const Vec3* x, const Index* row, Index begin, Index end, Real pad,
            const Real* values_a = nullptr, const Real* values_b = nullptr) {
    // The lanes are assembled in vector registers and stored whole: a lane stored alone and then
    // loaded with its chunk would stall store-to-load forwarding. The lists pad each row's last
    // chunk with valid indices (FixedStrideLists); lanes past `end` then take the pad offset.
    const Index* n = row + begin;
    const Real* xs = x->data();
    const LaneMask live = LaneMask{0, 1, 2, 3, 4, 5, 6, 7} < static_cast<long long>(end - begin);
    Lanes px, py, pz, va{}, vb{};
    gather(px, xs, n, 3, 0);
    gather(py, xs, n, 3, 1);
    gather(pz, xs, n, 3, 2);
    if (values_a) gather(va, values_a, n, 1, 0);
    if (values_b) gather(vb, values_b, n, 1, 0);
    store(rx, live ? xi.x() - px : pad);
    store(ry, live ? xi.y() - py : 0.0);
    store(rz, live ? xi.z() - pz : 0.0);
    store(a, live ? va : 0.0);
    store(b, live ? vb : 0.0);
  }

  /// w and g of every lane: the cubic spline of sph_kernel.hpp in branch-free form, with
  /// a = max(1 - q, 0), b = max(1/2 - q, 0):
  ///   W = sigma (2 a^3 - 8 b^3),   (dW/dr) / r = sigma / h (24 b^2 - 6 a^2) / r
  /// (zero for q >= 1 without a test, so pad lanes and list entries in the skin cost no branch).
  [[gnu::always_inline]] void evaluate(const CubicSplineKernel& kernel) {
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
