#pragma once
// Mesh file readers. Every failure is an InputError naming the file and, where it applies, the
// line, so that a bad mesh is reported like a bad scene key.
#include <string>

#include "moreau/geometry/meshes.hpp"

namespace moreau {

/// Triangles of a Wavefront OBJ file (polygons are fan-triangulated by tinyobjloader).
TriangleMesh read_obj_triangles(const std::string& path);

/// Tetrahedra (element type 4) of a Gmsh MSH 4.x ASCII file.
TetMesh read_gmsh_msh4(const std::string& path);

/// A TetGen mesh given as a .node and a .ele file (indices may start at 0 or 1).
TetMesh read_tetgen(const std::string& node_path, const std::string& ele_path);

/// Tetrahedralizes a closed OBJ surface with the `tetgen` program (quality mesh, radius-edge
/// ratio bound `quality`, optional maximum tetrahedron volume in m^3; 0 = unbounded).
TetMesh tetrahedralize_obj(const std::string& obj_path, Real quality, Real max_volume);

/// Checks that every tetrahedron has positive volume. A mesh whose tetrahedra are *all* negatively
/// oriented (a file convention) is flipped; a mix of orientations, or a tetrahedron whose volume
/// is below 1e-12 of the mesh's bounding-box volume, is an InputError naming `source`.
void orient_and_validate_tets(TetMesh& mesh, const std::string& source);

}  // namespace moreau
