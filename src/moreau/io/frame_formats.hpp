#pragma once
// The frame formats of settings.output.formats, each writing one object's frame (object_frame.hpp)
// to one file, whole or not at all (atomic_file.hpp).
//   vtk  .vtu (meshes) or .vtp (particles, polylines) with every array: ParaView, VisIt
//   obj  .obj of an object's surface triangles (cloth, soft bodies, rigid bodies, colliders):
//        Blender's File > Import > Wavefront (or an "OBJ sequence" add-on), Houdini, MeshLab
//   ply  binary .ply of an object's points with every point array as properties (particles,
//        grains, continua, rods): Blender's File > Import > Stanford PLY, Houdini, MeshLab
#include <string>

#include "moreau/io/object_frame.hpp"

namespace moreau {

/// settings.output.formats: the files each output step writes per object.
struct FrameFormats {
  bool vtk = true, obj = false, ply = false;
  bool any() const { return vtk || obj || ply; }
};

/// The file extension the VTK writer gives this frame: "vtu" or "vtp".
const char* vtk_extension(const ObjectFrame& frame);
void write_vtk_frame(const std::string& path, const ObjectFrame& frame);

/// Whether the frame has a surface for OBJ, and whether it is a point set for PLY.
bool has_surface(const ObjectFrame& frame);
bool is_point_set(const ObjectFrame& frame);

/// Wavefront OBJ: one object `name`, its vertices (m, 9 significant digits: exact in single
/// precision) and triangles, counter-clockwise seen from outside.
void write_obj_frame(const std::string& path, const std::string& name, const ObjectFrame& frame);

/// Stanford PLY, binary little-endian: element vertex with double x, y, z, then each point vector
/// array as <name>_x, <name>_y, <name>_z and each point scalar array as <name>.
void write_ply_frame(const std::string& path, const std::string& name, const ObjectFrame& frame);

}  // namespace moreau
