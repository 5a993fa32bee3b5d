#include "moreau/io/vtk_writer.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cstdint>
#include <fstream>
#include <stdexcept>

#include "moreau/io/atomic_file.hpp"

namespace moreau {

namespace {

/// Collects the binary blocks of the appended section and their offsets.
struct AppendedData {
  std::string bytes;
  template <class T>
  std::uint64_t add(const std::vector<T>& values) {
    const std::uint64_t offset = bytes.size();
    const std::uint64_t size = values.size() * sizeof(T);
    bytes.append(reinterpret_cast<const char*>(&size), sizeof(size));
    bytes.append(reinterpret_cast<const char*>(values.data()), size);
    return offset;
  }
};

std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(v.size() * 3);
  for (const auto& p : v) out.insert(out.end(), {p.x(), p.y(), p.z()});
  return out;
}

void write_file(const std::string& path, const std::string& xml, const AppendedData& data) {
  AtomicFile file(path);
  std::ofstream& out = file.stream();
  out << xml;
  out.write(data.bytes.data(), static_cast<std::streamsize>(data.bytes.size()));
  out << "\n</AppendedData>\n</VTKFile>\n";
  file.commit();
}

}  // namespace

namespace {

// The <PointData> or <CellData> section of vector and scalar arrays.
std::string data_section(const char* tag, const std::vector<VtkPointArray>& vectors,
                         const std::vector<VtkScalarArray>& scalars, AppendedData& data) {
  std::string xml = fmt::format("<{}>\n", tag);
  for (const auto& a : vectors)
    xml += fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{}\"/>\n",
                       a.name, data.add(flatten(a.values)));
  for (const auto& a : scalars)
    xml += fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"1\" format=\"appended\" offset=\"{}\"/>\n",
                       a.name, data.add(std::vector<double>(a.values.begin(), a.values.end())));
  return xml + fmt::format("</{}>\n", tag);
}

// A poly-data file whose cells are `cell_points` consecutive points each, in the <Verts> or
// <Lines> section.
void write_poly_data(const std::string& path, const std::vector<Vec3>& points, const char* section, size_t cells,
                     const std::vector<std::int64_t>& conn, const std::vector<VtkPointArray>& point_vectors,
                     const std::vector<VtkScalarArray>& point_scalars, const std::vector<VtkPointArray>& cell_vectors,
                     const std::vector<VtkScalarArray>& cell_scalars, int points_per_cell) {
  AppendedData data;
  const bool lines = std::string(section) == "Lines";
  std::string xml;
  xml += "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  xml += "<PolyData>\n";
  xml += fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" "
                     "NumberOfPolys=\"0\">\n",
                     points.size(), lines ? 0 : cells, lines ? cells : 0);
  xml += data_section("PointData", point_vectors, point_scalars, data);
  if (!cell_vectors.empty() || !cell_scalars.empty()) xml += data_section("CellData", cell_vectors, cell_scalars, data);
  xml += "<Points>\n";
  xml += fmt::format("<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{}\"/>\n",
                     data.add(flatten(points)));
  xml += fmt::format("</Points>\n<{}>\n", section);
  std::vector<std::int64_t> offsets(cells);
  for (size_t c = 0; c < cells; ++c) offsets[c] = static_cast<std::int64_t>(points_per_cell * (c + 1));
  xml += fmt::format("<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{}\"/>\n", data.add(conn));
  xml += fmt::format("<DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{}\"/>\n", data.add(offsets));
  xml += fmt::format("</{}>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_", section);
  write_file(path, xml, data);
}

}  // namespace

void write_vtp(const std::string& path, const std::vector<Vec3>& points, const std::vector<VtkPointArray>& vector_arrays,
               const std::vector<VtkScalarArray>& scalar_arrays) {
  std::vector<std::int64_t> conn(points.size());
  for (size_t p = 0; p < points.size(); ++p) conn[p] = static_cast<std::int64_t>(p);
  write_poly_data(path, points, "Verts", points.size(), conn, vector_arrays, scalar_arrays, {}, {}, 1);
}

void write_polyline_vtp(const std::string& path, const std::vector<Vec3>& points,
                        const std::vector<VtkPointArray>& point_vectors, const std::vector<VtkScalarArray>& point_scalars,
                        const std::vector<VtkPointArray>& cell_vectors, const std::vector<VtkScalarArray>& cell_scalars) {
  const size_t cells = points.empty() ? 0 : points.size() - 1;
  std::vector<std::int64_t> conn;
  for (size_t c = 0; c < cells; ++c) {
    conn.push_back(static_cast<std::int64_t>(c));
    conn.push_back(static_cast<std::int64_t>(c + 1));
  }
  write_poly_data(path, points, "Lines", cells, conn, point_vectors, point_scalars, cell_vectors, cell_scalars, 2);
}

void write_vtu(const std::string& path, const std::vector<Vec3>& points, const std::vector<Index>& connectivity,
               int nodes_per_cell, VtkCell cell_type, const std::vector<VtkPointArray>& point_arrays,
               const std::vector<VtkCellArray>& cell_arrays, const std::vector<VtkScalarArray>& point_scalars) {
  const size_t cells = connectivity.size() / nodes_per_cell;
  AppendedData data;
  std::string xml;
  xml += "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  xml += "<UnstructuredGrid>\n";
  xml += fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", points.size(), cells);
  xml += data_section("PointData", point_arrays, point_scalars, data);
  xml += "<CellData>\n";
  for (const auto& a : cell_arrays)
    xml += fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>\n",
                       a.name, a.components, data.add(std::vector<double>(a.values.begin(), a.values.end())));
  xml += "</CellData>\n<Points>\n";
  xml += fmt::format("<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{}\"/>\n",
                     data.add(flatten(points)));
  xml += "</Points>\n<Cells>\n";
  std::vector<std::int64_t> conn(connectivity.begin(), connectivity.end()), offsets(cells);
  std::vector<std::uint8_t> types(cells, static_cast<std::uint8_t>(cell_type));
  for (size_t c = 0; c < cells; ++c) offsets[c] = static_cast<std::int64_t>((c + 1) * nodes_per_cell);
  xml += fmt::format("<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{}\"/>\n", data.add(conn));
  xml += fmt::format("<DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{}\"/>\n", data.add(offsets));
  xml += fmt::format("<DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"{}\"/>\n", data.add(types));
  xml += "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  write_file(path, xml, data);
}

std::string safe_file_name(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  // A leading dot would hide the file: a scene named "../../x" gives "___.._x", not ".._.._x".
  for (char& c : s) {
    if (c != '.') break;
    c = '_';
  }
  return s.empty() ? std::string("_") : s;
}

}  // namespace moreau
