#include "moreau/fluids/fluid_neighbors.hpp"

#include <algorithm>

#include "moreau/fluids/pair_chunks.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

namespace {

// Moves values[k] <- values[order[k]] for the first n entries, through a same-sized scratch
// buffer. Every thread calls it (orphaned omp for, then one thread swaps the buffers).
template <class T>
void permute(std::vector<T>& values, std::vector<T>& scratch, const std::vector<Index>& order, Index n) {
#pragma omp for schedule(static)
  for (Index k = 0; k < n; ++k) scratch[k] = values[order[k]];
#pragma omp single
  values.swap(scratch);
}

bool moved_past_skin(const Model& model, const FluidState& fluid, Real time) {
  const FluidModel& fm = model.fluid;
  if (fm.neighbor_skin <= 0) return true;  // lists hold no spare distance: rebuild every substep
  const Real limit2 = 0.25 * fm.neighbor_skin * fm.neighbor_skin;
  for (Index i = 0; i < fluid.count; ++i)
    if ((fluid.position[i] - fluid.listed_position[i]).squaredNorm() > limit2) return true;
  if (fm.boundary.moving)
    for (const Collider& c : model.colliders)
      if (((time - fluid.listed_time) * c.velocity).squaredNorm() > limit2) return true;
  return false;
}

// Carries every per-particle array along the grid's z-order sort (every thread).
void permute_particles(FluidState& fluid, FluidScratch& scratch) {
  const Index n = fluid.count;
  const std::vector<Index>& order = fluid.fluid_grid.order();
  permute(fluid.position, scratch.reorder_vec, order, n);
  permute(fluid.velocity, scratch.reorder_vec, order, n);
  permute(scratch.substep_start, scratch.reorder_vec, order, n);
  permute(fluid.phase, scratch.reorder_index, order, n);
  permute(fluid.id, scratch.reorder_index, order, n);
  permute(fluid.inv_mass, scratch.reorder_real, order, n);
  permute(fluid.mass, scratch.reorder_real, order, n);
  permute(fluid.pressure, scratch.reorder_real, order, n);
  permute(fluid.density, scratch.reorder_real, order, n);
  permute(fluid.enthalpy, scratch.reorder_real, order, n);
  permute(fluid.viscosity, scratch.reorder_real, order, n);
  permute(fluid.smoke, scratch.reorder_real, order, n);
  permute(fluid.release_time, scratch.reorder_real, order, n);
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) fluid.listed_position[i] = fluid.position[i];
}

// Writes row i of `lists` with the points of `ranges` (mapped through `map`, or identity) that lie
// within sqrt(r2) of x_i, skipping `self`. Returns the true count (may exceed the row's capacity,
// stride - 1). Branch-free: every candidate is written at the current end of the row and the end
// advances only if it is a neighbour (about one candidate in six is), so no branch mispredicts;
// the row's last slot takes the writes once it is full.
template <class Map>
Index fill_row(FixedStrideLists& lists, Index i, const Vec3& xi, const Vec3* x, const CellRange* ranges,
               int range_count, Real r2, Index self, Map&& map) {
  Index* row = lists.entries.data() + static_cast<std::size_t>(i) * lists.stride;
  const Index last = lists.stride - 1;
  Index count = 0;
  for (int r = 0; r < range_count; ++r)
    for (Index k = ranges[r].first; k < ranges[r].second; ++k) {
      const Index j = map(k);
      const Vec3 d = x[j] - xi;
      const bool take = (j != self) & (d.x() * d.x() + d.y() * d.y() + d.z() * d.z() < r2);
      row[count < last ? count : last] = j;
      count += take;
    }
  // The row's last chunk is whole: its unused lanes repeat the first neighbour, so the pair loops
  // load a chunk's indices as one vector (pair_chunks.hpp).
  const Index whole = std::min<Index>((count + kPairChunk - 1) / kPairChunk * kPairChunk, lists.stride);
  for (Index k = count; k < whole; ++k) row[k] = row[0];
  return count;
}

void fill_rows(const Model& model, FluidState& fluid) {
  const FluidModel& fm = model.fluid;
  const Real radius = fm.support() + fm.neighbor_skin;
  const Real r2 = radius * radius;
  const CellGrid& grid = fluid.fluid_grid;
  const bool walls = fm.boundary.size() > 0, solids = fm.solid.size() > 0;
  const std::vector<Index>& boundary_order = fluid.boundary_grid.order();
  const std::vector<Index>& solid_order = fluid.solid_grid.order();
  const Index cells = grid.cell_count();
#pragma omp for schedule(static)
  for (Index c = 0; c < cells; ++c) {
    CellRange fluid_ranges[27], wall_ranges[27], solid_ranges[27];
    const int nf = grid.neighbor_ranges(grid.cell_coord(c), fluid_ranges);
    const int nb = walls ? fluid.boundary_grid.neighbor_ranges(grid.cell_coord(c), wall_ranges) : 0;
    const int ns = solids ? fluid.solid_grid.neighbor_ranges(grid.cell_coord(c), solid_ranges) : 0;
    for (Index i = grid.cell_begin(c); i < grid.cell_begin(c + 1); ++i) {
      const Vec3 xi = fluid.position[i];
      fluid.fluid_neighbors.count[i] = fill_row(fluid.fluid_neighbors, i, xi, fluid.position.data(), fluid_ranges, nf,
                                                r2, i, [](Index k) { return k; });
      fluid.boundary_neighbors.count[i] =
          fill_row(fluid.boundary_neighbors, i, xi, fluid.boundary_position.data(), wall_ranges, nb, r2, -1,
                   [&](Index k) { return boundary_order[k]; });
      fluid.solid_neighbors.count[i] = fill_row(fluid.solid_neighbors, i, xi, fluid.solid_position.data(),
                                                solid_ranges, ns, r2, -1, [&](Index k) { return solid_order[k]; });
    }
  }
  // The reverse lists: the fluid particles of each solid sample (the fluid is in grid order).
  const CellGrid& solid_grid = fluid.solid_grid;
  const Index solid_cells = solids ? solid_grid.cell_count() : 0;
#pragma omp for schedule(static)
  for (Index c = 0; c < solid_cells; ++c) {
    CellRange fluid_ranges[27];
    const int nf = grid.neighbor_ranges(solid_grid.cell_coord(c), fluid_ranges);
    for (Index k = solid_grid.cell_begin(c); k < solid_grid.cell_begin(c + 1); ++k) {
      const Index s = solid_order[k];
      fluid.solid_fluids.count[s] = fill_row(fluid.solid_fluids, s, fluid.solid_position[s], fluid.position.data(),
                                             fluid_ranges, nf, r2, -1, [](Index j) { return j; });
    }
  }
}

// Grows a list's rows to hold its longest row (plus headroom and the spare slot fill_row writes
// into). Returns true if it grew.
bool grow_if_overflowed(FixedStrideLists& lists, Index n) {
  Index longest = 0;
  for (Index i = 0; i < n; ++i) longest = std::max(longest, lists.count[i]);
  if (longest <= lists.stride - 1) return false;
  lists.stride = (longest + longest / 4 + 8 + kPairChunk - 1) / kPairChunk * kPairChunk;
  lists.entries.resize(lists.count.size() * static_cast<std::size_t>(lists.stride));
  return true;
}

}  // namespace

void place_boundary_samples(const Model& model, FluidState& fluid, Real time) {
  const FluidBoundarySamples& b = model.fluid.boundary;
  const Index n = b.size();
#pragma omp for schedule(static)
  for (Index k = 0; k < n; ++k) {
    const Collider& c = model.colliders[b.collider[k]];
    fluid.boundary_position[k] = c.position_at(time) + b.local_position[k];
  }
}

bool update_fluid_neighbors(const Model& model, FluidState& fluid, FluidScratch& scratch, Real time) {
  const FluidModel& fm = model.fluid;
  const bool moving_walls = fm.boundary.moving;
#pragma omp single
  {
    // Solid samples move with cloth and soft bodies: their lists are rebuilt every substep, and
    // the reverse lists need the fluid grid of the current positions, so the fluid's too.
    fluid.rebuilding = fluid.lists_stale || fm.solid.size() > 0 || moved_past_skin(model, fluid, time);
    if (fluid.rebuilding) {
      fluid.fluid_grid.build(fluid.position.data(), fluid.count, fluid.frame);
      fluid.listed_time = time;
      fluid.lists_stale = false;
      ++fluid.list_builds;
    }
  }
  if (!fluid.rebuilding) return false;
  permute_particles(fluid, scratch);
  if (moving_walls || !fluid.boundary_grid_built) {
    // Moving walls were placed by the step at the start of this substep; static ones once, here.
    if (!moving_walls) place_boundary_samples(model, fluid, time);
#pragma omp single
    {
      fluid.boundary_grid.build(fluid.boundary_position.data(), fm.boundary.size(), fluid.frame);
      fluid.boundary_grid_built = true;
    }
  }
  if (fm.solid.size() > 0) {
#pragma omp single
    fluid.solid_grid.build(fluid.solid_position.data(), fm.solid.size(), fluid.frame);
  }
  fill_rows(model, fluid);
#pragma omp single
  fluid.rebuilding = grow_if_overflowed(fluid.fluid_neighbors, fluid.count) |
                     grow_if_overflowed(fluid.boundary_neighbors, fluid.count) |
                     grow_if_overflowed(fluid.solid_neighbors, fluid.count) |
                     grow_if_overflowed(fluid.solid_fluids, fm.solid.size());
  if (fluid.rebuilding) fill_rows(model, fluid);
#pragma omp barrier
  return true;
}

}  // namespace moreau
