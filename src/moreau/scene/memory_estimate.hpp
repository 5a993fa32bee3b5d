#pragma once
// Refuses, before anything is allocated, a scene whose meshes or particles cannot fit in memory:
// a mesh of 10^10 cells failed at once with bad_alloc, and a soft body of 8·10^9 cells grew to
// 3 GB before it did. Each large array a scene key implies is estimated from its count times a
// cost per item measured on this engine (peak resident memory of a run over its item count,
// rounded down, so the estimate is a lower bound), and compared with the memory limit.
#include <string>

#include "moreau/math/types.hpp"
#include "moreau/scene/spec_place.hpp"

namespace moreau {

/// Bytes per item, lower bounds of what a run keeps per item (measured on 64k to 400k items).
namespace memory_cost {
inline constexpr double tetrahedron = 300;       // XPBD soft body (measured 410 B: particles, constraints, solver)
inline constexpr double cloth_cell = 300;        // XPBD cloth grid cell (two triangles; measured 410 B)
inline constexpr double fluid_particle = 2000;   // particle fluid (measured 2.3 kB: neighbour lists, kernel cache)
inline constexpr double fluid_wall_sample = 100; // a collider's wall sample for the fluid (60 B kept, plus the
                                                 // neighbour search that computes the volumes)
inline constexpr double solid_cell_2d = 3000;    // FEM quad4 cell with its sparse Cholesky factor (measured 4.4 kB)
inline constexpr double solid_cell_3d = 10000;   // FEM hex8 cell (measured 40 kB at 27,000 cells; grows with size)
inline constexpr double flow_cell_2d = 6000;     // Navier-Stokes Q1Q1 cell with its LU factors (measured 11 kB)
inline constexpr double flow_cell_3d = 30000;    // Navier-Stokes hex8 cell
}  // namespace memory_cost

/// The limit: `--memory-limit` (GB) if given, else 80 % of this machine's physical memory.
double memory_limit_bytes();
void set_memory_limit_bytes(double bytes);

/// Fails (exit 2) at `key` of `at` if `count` items of `bytes_each` exceed the limit, naming the
/// count, the estimate and the limit.
void check_memory(const SpecPlace& at, const std::string& key, double count, double bytes_each, const std::string& items);

}  // namespace moreau
