#pragma once
// Tile batches: contacts grouped by the spatial tile they were found in, the tiles in eight
// colours. A tile's contacts are solved one after another (Gauss-Seidel in the order of the
// Morton-sorted grid, so the particles a tile touches stay in cache while it is solved); the
// tiles of one colour run in parallel, the colours one after another.
//
// Why tiles of one colour touch disjoint particles: a tile is a cube of 4 x 4 x 4 grid cells
// aligned on the grid, and its colour is the parity of its integer coordinates along x, y and z.
// Two tiles of one colour differ by an even, nonzero number of tiles along some axis, so a whole
// tile (4 cells wide) lies between them. A contact found from a particle in tile A reaches a
// particle at most D away from it, so every particle it moves lies within D of A; a particle moved
// from both A and B would lie within D of each, which needs 4 cells <= 2 D. The pair search's
// cells are 2.5 r_max + g_max wide and its pairs at most D = 4 r_max + g_max apart
// (collision/particle_contacts.cpp): 10 r_max + 4 g_max > 8 r_max + 2 g_max. The result does
// not depend on the thread count (a tile is always solved whole, by one thread, in one order).
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// Cells per tile along each axis, and the tile's colour count (2^3: the parity of its coordinates).
inline constexpr int kTileCells = 4;
inline constexpr int kTileColors = 8;
static_assert(kTileCells == 4, "the separation argument above needs tiles of 4 cells of 2.5 r_max + g_max");
static_assert(kTileColors == 8, "a tile's colour is the parity of its three coordinates");

struct TileBatches {
  std::vector<Index> color_tiles{0};  // colour c holds the tiles [color_tiles[c], color_tiles[c+1])
  std::vector<Index> tile_offsets{0};  // tile t holds the contacts [tile_offsets[t], tile_offsets[t+1])

  Index color_count() const { return static_cast<Index>(color_tiles.size()) - 1; }
  void clear() {
    color_tiles.assign(1, 0);
    tile_offsets.assign(1, 0);
  }
};

/// Runs body(k) for every contact k, tile by tile, colour after colour. Must be called from inside
/// an OpenMP parallel region (or serially): each colour is an orphaned `omp for` over its tiles.
/// Dynamic scheduling balances tiles of unequal size and changes no result (tiles are independent).
template <class Body>
void for_each_by_tile(const TileBatches& batches, Body&& body) {
  for (Index c = 0; c < batches.color_count(); ++c) {
    const Index begin = batches.color_tiles[c], end = batches.color_tiles[c + 1];
#pragma omp for schedule(dynamic, 4)
    for (Index t = begin; t < end; ++t)
      for (Index k = batches.tile_offsets[t]; k < batches.tile_offsets[t + 1]; ++k) body(k);
  }
}

}  // namespace moreau
