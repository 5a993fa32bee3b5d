#pragma once
// One scene object's geometry and fields at one output step, as every frame format reads it:
// VTK (.vtu/.vtp, all of it), OBJ (the surface triangles) and PLY (the points with their arrays).
#include <array>
#include <vector>

#include "moreau/io/vtk_writer.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

struct ObjectFrame {
  enum class Cells { points, triangles, tetrahedra, polyline };
  Cells cells = Cells::points;
  std::vector<Vec3> points;                   // m
  std::vector<Index> connectivity;            // triangles or tetrahedra, by index into points
  std::vector<std::array<Index, 3>> surface;  // the triangles a surface format draws (a soft body's boundary)
  std::vector<VtkPointArray> point_vectors;
  std::vector<VtkScalarArray> point_scalars;
  std::vector<VtkPointArray> cell_vectors;    // polyline: one per segment
  std::vector<VtkScalarArray> cell_scalars;
};

/// The frame of `object` in `state`. Planes (infinite colliders) are drawn as squares of
/// `plane_half_size` around their reference point.
ObjectFrame object_frame(const Model& model, const ObjectInfo& object, const State& state, Real plane_half_size);

}  // namespace moreau
