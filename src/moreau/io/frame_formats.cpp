#include "moreau/io/frame_formats.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstring>

#include "moreau/io/atomic_file.hpp"

namespace moreau {

static_assert(std::endian::native == std::endian::little, "the PLY writer writes the host's bytes as little-endian");

const char* vtk_extension(const ObjectFrame& frame) {
  return frame.cells == ObjectFrame::Cells::triangles || frame.cells == ObjectFrame::Cells::tetrahedra ? "vtu" : "vtp";
}

void write_vtk_frame(const std::string& path, const ObjectFrame& f) {
  switch (f.cells) {
    case ObjectFrame::Cells::points: write_vtp(path, f.points, f.point_vectors, f.point_scalars); break;
    case ObjectFrame::Cells::triangles:
      write_vtu(path, f.points, f.connectivity, 3, VtkCell::triangle, f.point_vectors, {}, f.point_scalars);
      break;
    case ObjectFrame::Cells::tetrahedra:
      write_vtu(path, f.points, f.connectivity, 4, VtkCell::tetra, f.point_vectors, {}, f.point_scalars);
      break;
    case ObjectFrame::Cells::polyline:
      write_polyline_vtp(path, f.points, f.point_vectors, f.point_scalars, f.cell_vectors, f.cell_scalars);
      break;
  }
}

bool has_surface(const ObjectFrame& f) {
  return f.cells == ObjectFrame::Cells::triangles || f.cells == ObjectFrame::Cells::tetrahedra;
}

bool is_point_set(const ObjectFrame& f) { return !has_surface(f); }

void write_obj_frame(const std::string& path, const std::string& name, const ObjectFrame& f) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "# moreau frame: {} vertices, {} triangles, metres\no {}\n", f.points.size(),
                 f.surface.size(), name);
  for (const Vec3& x : f.points) fmt::format_to(std::back_inserter(out), "v {:.9g} {:.9g} {:.9g}\n", x.x(), x.y(), x.z());
  for (const auto& t : f.surface) fmt::format_to(std::back_inserter(out), "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  write_file_atomically(path, fmt::to_string(out));
}

void write_ply_frame(const std::string& path, const std::string& name, const ObjectFrame& f) {
  const std::size_t n = f.points.size();
  std::string header = fmt::format("ply\nformat binary_little_endian 1.0\ncomment moreau frame of '{}', SI units\n"
                                   "element vertex {}\nproperty double x\nproperty double y\nproperty double z\n",
                                   name, n);
  for (const VtkPointArray& a : f.point_vectors)
    for (const char* axis : {"x", "y", "z"}) header += fmt::format("property double {}_{}\n", a.name, axis);
  for (const VtkScalarArray& a : f.point_scalars) header += fmt::format("property double {}\n", a.name);
  header += "end_header\n";
  const std::size_t row = 3 + 3 * f.point_vectors.size() + f.point_scalars.size();
  std::string bytes = header;
  bytes.resize(header.size() + n * row * sizeof(double));
  char* data = bytes.data() + header.size();
  const auto put = [&data](double value) {
    std::memcpy(data, &value, sizeof value);
    data += sizeof value;
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) put(f.points[i][d]);
    for (const VtkPointArray& a : f.point_vectors)
      for (int d = 0; d < 3; ++d) put(a.values[i][d]);
    for (const VtkScalarArray& a : f.point_scalars) put(a.values[i]);
  }
  write_file_atomically(path, bytes);
}

}  // namespace moreau
