// Mesh generators and readers (exact volumes and topology), and the VTK writers (the binary
// appended data read back value for value).
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "moreau/errors.hpp"
#include "moreau/geometry/mesh_generators.hpp"
#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/io/vtk_writer.hpp"
#include "test_helpers.hpp"
#include "vtk_read.hpp"

using namespace moreau;
using moreau::test::read_appended_float64;

namespace {

Real total_volume(const TetMesh& m) {
  Real v = 0;
  for (const auto& t : m.tets) v += tet_signed_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
  return v;
}

// Every face of a conforming tetrahedral mesh is shared by two tetrahedra or lies on the boundary.
std::map<std::array<Index, 3>, int> face_use_counts(const TetMesh& m) {
  std::map<std::array<Index, 3>, int> uses;
  static constexpr int kFaces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& t : m.tets)
    for (const auto& f : kFaces) {
      std::array<Index, 3> face{t[f[0]], t[f[1]], t[f[2]]};
      std::sort(face.begin(), face.end());
      ++uses[face];
    }
  return uses;
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace

TEST(MeshGenerators, BoxSplitsFillTheBoxAndConform) {
  for (CellSplit split : {CellSplit::six, CellSplit::five}) {
    const int nx = 3, ny = 2, nz = 4;
    const TetMesh m = make_box_tets(Vec3(0, 0, 0), Vec3(1.5, 0.5, 2.0), {nx, ny, nz}, split);
    EXPECT_EQ(m.tets.size(), static_cast<size_t>(nx * ny * nz * (split == CellSplit::six ? 6 : 5)));
    EXPECT_NEAR(total_volume(m), 1.5 * 0.5 * 2.0, 1e-12);
    for (const auto& t : m.tets)
      EXPECT_GT(tet_signed_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]), 0);
    // Conforming: no face used more than twice, and the boundary is exactly two triangles per
    // boundary cell face (a face diagonal that did not match its neighbour's would add more).
    int boundary = 0;
    for (const auto& [face, uses] : face_use_counts(m)) {
      EXPECT_LE(uses, 2);
      boundary += uses == 1;
    }
    EXPECT_EQ(boundary, 2 * 2 * (nx * ny + ny * nz + nx * nz));
    EXPECT_EQ(tet_boundary_faces(m).size(), static_cast<size_t>(boundary));
  }
}

TEST(MeshReaders, GmshTetGenAndObjFilesGiveTheExpectedMeshes) {
  const std::string dir = test::temp_dir("readers");
  // A unit cube's 5-tet split written as Gmsh 4.1 ASCII (node tags 11..18, one node block).
  const TetMesh cube = make_box_tets(Vec3::Zero(), Vec3::Ones(), {1, 1, 1}, CellSplit::five);
  std::string msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 8 11 18\n3 1 0 8\n";
  for (int i = 0; i < 8; ++i) msh += fmt::format("{}\n", 11 + i);
  for (const auto& v : cube.vertices) msh += fmt::format("{} {} {}\n", v.x(), v.y(), v.z());
  msh += "$EndNodes\n$Elements\n1 5 1 5\n3 1 4 5\n";
  for (size_t k = 0; k < cube.tets.size(); ++k) {
    const auto& t = cube.tets[k];
    msh += fmt::format("{} {} {} {} {}\n", k + 1, 11 + t[0], 11 + t[1], 11 + t[2], 11 + t[3]);
  }
  msh += "$EndElements\n";
  write_text(dir + "/cube.msh", msh);
  const TetMesh from_msh = read_gmsh_msh4(dir + "/cube.msh");
  EXPECT_EQ(from_msh.vertices.size(), 8u);
  EXPECT_EQ(from_msh.tets.size(), 5u);
  EXPECT_NEAR(total_volume(from_msh), 1.0, 1e-14);

  // The same mesh as TetGen .node/.ele with 1-based indices.
  std::string node = "8 3 0 0\n", ele = "5 4 0\n";
  for (int i = 0; i < 8; ++i) node += fmt::format("{} {} {} {}\n", i + 1, cube.vertices[i].x(), cube.vertices[i].y(), cube.vertices[i].z());
  for (size_t k = 0; k < cube.tets.size(); ++k) {
    const auto& t = cube.tets[k];
    ele += fmt::format("{} {} {} {} {}\n", k + 1, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
  }
  write_text(dir + "/cube.node", node);
  write_text(dir + "/cube.ele", ele);
  const TetMesh from_tetgen = read_tetgen(dir + "/cube.node", dir + "/cube.ele");
  EXPECT_EQ(from_tetgen.tets.size(), 5u);
  EXPECT_NEAR(total_volume(from_tetgen), 1.0, 1e-14);

  // A cube surface as OBJ quads: fan-triangulated into 12 triangles; tetgen fills it exactly.
  write_text(dir + "/cube.obj",
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  EXPECT_EQ(read_obj_triangles(dir + "/cube.obj").triangles.size(), 12u);
  TetMesh filled = tetrahedralize_obj(dir + "/cube.obj", 1.5, 0.01);
  orient_and_validate_tets(filled, "cube.obj");
  EXPECT_GE(filled.tets.size(), 100u);  // max_volume 0.01 m^3 forces at least 100 tetrahedra
  EXPECT_NEAR(total_volume(filled), 1.0, 1e-12);

  // A truncated element line names file and line ("file:line: problem").
  write_text(dir + "/bad.ele", "5 4 0\n1 1 2 3\n");
  try {
    read_tetgen(dir + "/cube.node", dir + "/bad.ele");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.ele"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.ele:2:"), std::string::npos) << e.what();
  }
}

TEST(VtkWriters, AppendedBinaryDataReadsBackExactly) {
  const std::string dir = test::temp_dir("vtk");
  const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(1, 0.5, -2), Vec3(1e-300, 3.25, 7)};
  const std::vector<Vec3> velocity{Vec3(1, 2, 3), Vec3(-4, 5, -6), Vec3(0.1, 0.2, 0.3)};
  write_vtp(dir + "/particles.vtp", points, {{"velocity", velocity}}, {{"radius", {0.1, 0.2, 0.3}}});
  const auto v = read_appended_float64(dir + "/particles.vtp", "velocity");
  ASSERT_EQ(v.size(), 9u);
  for (int p = 0; p < 3; ++p)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(v[3 * p + d], velocity[p][d]);
  EXPECT_EQ(read_appended_float64(dir + "/particles.vtp", "radius"), (std::vector<double>{0.1, 0.2, 0.3}));

  write_vtu(dir + "/tri.vtu", points, {0, 1, 2}, 3, VtkCell::triangle, {{"displacement", velocity}});
  const auto d = read_appended_float64(dir + "/tri.vtu", "displacement");
  ASSERT_EQ(d.size(), 9u);
  EXPECT_EQ(d[4], 5.0);
  std::ifstream in(dir + "/particles.vtp");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("NumberOfVerts=\"3\""), std::string::npos);
}
