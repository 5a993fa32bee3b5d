#pragma once
// Colour batches: the constraints of one family sorted so that each colour is a contiguous range
// in which no two constraints move the same particle. A colour is a parallel loop; colours run
// one after another (parallel Gauss-Seidel). The result does not depend on the thread count
// because constraints in one colour touch disjoint particles.
#include <algorithm>
#include <array>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct ColorBatches {
  std::vector<Index> offsets{0};  // colour c is [offsets[c], offsets[c+1])
  Index color_count() const { return static_cast<Index>(offsets.size()) - 1; }
};

/// Greedy first-fit colouring. `stencils[k]` lists the particles of constraint k (-1 pads unused
/// slots). Particles with zero inverse mass never move, so they do not create conflicts.
/// Returns the permutation that sorts constraints by colour, and fills `batches`.
std::vector<Index> color_constraints(const std::vector<std::array<Index, 4>>& stencils,
                                     const std::vector<Real>& particle_inv_mass, ColorBatches& batches);

/// Reorders `values` so that values[new k] = old values[permutation[k]].
template <class T>
void apply_permutation(std::vector<T>& values, const std::vector<Index>& permutation) {
  if (values.empty()) return;
  std::vector<T> sorted;
  sorted.reserve(values.size());
  for (Index k : permutation) sorted.push_back(values[k]);
  values.swap(sorted);
}

/// apply_permutation on each of a family's per-constraint arrays.
template <class... Arrays>
void apply_permutation_to_all(const std::vector<Index>& permutation, Arrays&... arrays) {
  (apply_permutation(arrays, permutation), ...);
}

/// Runs body(k) for every constraint k, colour after colour. Must be called from inside an OpenMP
/// parallel region (or serially): each colour is an orphaned `omp for` with its implicit barrier.
template <class Body>
void for_each_by_color(const ColorBatches& batches, Body&& body) {
  for (Index c = 0; c < batches.color_count(); ++c) {
    const Index begin = batches.offsets[c], end = batches.offsets[c + 1];
#pragma omp for schedule(static)
    for (Index k = begin; k < end; ++k) body(k);
  }
}

}  // namespace moreau
