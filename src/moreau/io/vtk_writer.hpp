#pragma once
// VTK XML writers (ParaView, VisIt, Blender importers). Unstructured grids (.vtu) carry point
// arrays; the data is raw binary in an appended section (little-endian, UInt64 headers), which
// keeps frames small and fast to write.
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// VTK cell type ids.
enum class VtkCell : unsigned char { line = 3, triangle = 5, quad = 9, tetra = 10, hexahedron = 12 };

struct VtkPointArray {
  std::string name;
  std::vector<Vec3> values;
};

struct VtkScalarArray {
  std::string name;
  std::vector<Real> values;
};

/// Per-cell values with `components` numbers per cell (1: scalar, 6: a symmetric tensor in VTK's
/// order xx, yy, zz, xy, yz, xz, which ParaView shows as a tensor).
struct VtkCellArray {
  std::string name;
  int components = 1;
  std::vector<Real> values;
};

/// Writes an unstructured grid of one cell type with 3-component point arrays and cell arrays.
void write_vtu(const std::string& path, const std::vector<Vec3>& points, const std::vector<Index>& connectivity,
               int nodes_per_cell, VtkCell cell_type, const std::vector<VtkPointArray>& point_arrays,
               const std::vector<VtkCellArray>& cell_arrays = {},
               const std::vector<VtkScalarArray>& point_scalars = {});

/// Writes particles as a poly-data file (.vtp): one vertex cell per point, so ParaView shows them
/// without a filter (use "Point Gaussian" with the `radius` array for spheres).
void write_vtp(const std::string& path, const std::vector<Vec3>& points, const std::vector<VtkPointArray>& vector_arrays,
               const std::vector<VtkScalarArray>& scalar_arrays);

/// Writes a polyline (.vtp) through `points`: one line cell per consecutive pair, with point and
/// cell arrays (cell k runs from point k to point k + 1).
void write_polyline_vtp(const std::string& path, const std::vector<Vec3>& points,
                        const std::vector<VtkPointArray>& point_vectors, const std::vector<VtkScalarArray>& point_scalars,
                        const std::vector<VtkPointArray>& cell_vectors, const std::vector<VtkScalarArray>& cell_scalars);

/// File-system-safe version of a scene or object name.
std::string safe_file_name(const std::string& name);

}  // namespace moreau
