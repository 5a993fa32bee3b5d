#include "moreau/geometry/mesh_readers.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "moreau/errors.hpp"
#include "moreau/geometry/gmsh_reader.hpp"
#include "moreau/geometry/line_reader.hpp"

namespace moreau {

namespace fs = std::filesystem;

TriangleMesh read_obj_triangles(const std::string& path) {
  if (!fs::exists(path)) throw InputError(fmt::format("{}: mesh file not found", path));
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config))
    throw InputError(fmt::format("{}: cannot read OBJ file: {}", path, reader.Error()));
  TriangleMesh mesh;
  const auto& v = reader.GetAttrib().vertices;
  for (size_t i = 0; i + 2 < v.size(); i += 3) mesh.vertices.emplace_back(v[i], v[i + 1], v[i + 2]);
  for (const auto& shape : reader.GetShapes())
    for (size_t f = 0; f + 2 < shape.mesh.indices.size(); f += 3)
      mesh.triangles.push_back({shape.mesh.indices[f].vertex_index, shape.mesh.indices[f + 1].vertex_index,
                                shape.mesh.indices[f + 2].vertex_index});
  if (mesh.triangles.empty()) throw InputError(fmt::format("{}: OBJ file has no faces", path));
  return mesh;
}

TetMesh read_gmsh_msh4(const std::string& path) {
  const GmshFile file = read_gmsh_file(path);
  TetMesh mesh;
  mesh.vertices = file.nodes;
  for (const GmshElementBlock& block : file.blocks) {
    if (block.type != GmshElementType::tet4) continue;  // only 4-node tetrahedra make up the volume
    for (size_t e = 0; e < block.nodes.size(); e += 4)
      mesh.tets.push_back({block.nodes[e], block.nodes[e + 1], block.nodes[e + 2], block.nodes[e + 3]});
  }
  if (mesh.tets.empty()) throw InputError(fmt::format("{}: no tetrahedra (element type 4) in the file", path));
  return mesh;
}

TetMesh read_tetgen(const std::string& node_path, const std::string& ele_path) {
  TetMesh mesh;
  LineReader nodes{open_or_throw(node_path), node_path};
  std::istringstream line;
  long count = 0;
  int dim = 0, attributes = 0, markers = 0;
  if (!nodes.next(line) || !(line >> count >> dim >> attributes >> markers) || dim != 3)
    nodes.fail("malformed .node header; expected '<points> 3 <attributes> <markers>'");
  std::unordered_map<long, Index> index_of;
  for (long i = 0; i < count; ++i) {
    long id;
    double x, y, z;
    if (!nodes.next(line) || !(line >> id >> x >> y >> z)) nodes.fail("malformed node line");
    index_of[id] = static_cast<Index>(mesh.vertices.size());
    mesh.vertices.emplace_back(x, y, z);
  }
  LineReader eles{open_or_throw(ele_path), ele_path};
  int per_tet = 0;
  if (!eles.next(line) || !(line >> count >> per_tet >> attributes) || per_tet != 4)
    eles.fail("malformed .ele header; expected '<tetrahedra> 4 <attributes>' (linear tetrahedra only)");
  for (long i = 0; i < count; ++i) {
    long id;
    std::array<long, 4> n{};
    if (!eles.next(line) || !(line >> id >> n[0] >> n[1] >> n[2] >> n[3])) eles.fail("malformed tetrahedron line");
    std::array<Index, 4> tet{};
    for (int k = 0; k < 4; ++k) {
      auto it = index_of.find(n[k]);
      if (it == index_of.end()) eles.fail(fmt::format("tetrahedron refers to unknown node {}", n[k]));
      tet[k] = it->second;
    }
    mesh.tets.push_back(tet);
  }
  return mesh;
}

TetMesh tetrahedralize_obj(const std::string& obj_path, Real quality, Real max_volume) {
  const TriangleMesh surface = read_obj_triangles(obj_path);
  // Write the surface as OFF into a private temporary directory and run tetgen on it.
  std::string dir_template = (fs::temp_directory_path() / "moreau-tetgen-XXXXXX").string();
  if (!mkdtemp(dir_template.data())) throw std::runtime_error("cannot create a temporary directory for tetgen");
  const fs::path dir = dir_template;
  const fs::path off = dir / "surface.off";
  {
    std::ofstream out(off);
    out << "OFF\n" << surface.vertices.size() << ' ' << surface.triangles.size() << " 0\n";
    out.precision(17);
    for (const auto& v : surface.vertices) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& t : surface.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  std::string switches = fmt::format("-pq{}", quality);
  if (max_volume > 0) switches += fmt::format("a{}", max_volume);
  const std::string command = fmt::format("tetgen {}Q '{}' > '{}' 2>&1", switches, off.string(), (dir / "log").string());
  const int status = std::system(command.c_str());
  if (status != 0) {
    std::ifstream log(dir / "log");
    std::stringstream text;
    text << log.rdbuf();
    fs::remove_all(dir);
    throw InputError(fmt::format("{}: tetgen could not tetrahedralize the surface (is it closed and "
                                 "non-self-intersecting?): {}",
                                 obj_path, text.str()));
  }
  TetMesh mesh = read_tetgen((dir / "surface.1.node").string(), (dir / "surface.1.ele").string());
  fs::remove_all(dir);
  return mesh;
}

void orient_and_validate_tets(TetMesh& mesh, const std::string& source) {
  if (mesh.tets.empty()) throw InputError(fmt::format("{}: the mesh has no tetrahedra", source));
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Real tiny = 1e-12 * (hi - lo).prod();
  size_t negative = 0;
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& k = mesh.tets[t];
    for (Index i : k)
      if (i < 0 || i >= static_cast<Index>(mesh.vertices.size()))
        throw InputError(fmt::format("{}: tetrahedron {} refers to vertex {} which does not exist", source, t, i));
    const Real v = tet_signed_volume(mesh.vertices[k[0]], mesh.vertices[k[1]], mesh.vertices[k[2]], mesh.vertices[k[3]]);
    if (std::abs(v) <= tiny)
      throw InputError(fmt::format("{}: tetrahedron {} is degenerate (volume {:.3g} m^3)", source, t, v));
    if (v < 0) ++negative;
  }
  if (negative == mesh.tets.size()) {
    for (auto& k : mesh.tets) std::swap(k[2], k[3]);
  } else if (negative > 0) {
    throw InputError(fmt::format("{}: {} of {} tetrahedra are inverted (negative volume) while the others "
                                 "are not; fix the mesh orientation",
                                 source, negative, mesh.tets.size()));
  }
}

}  // namespace moreau
