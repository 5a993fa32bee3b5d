// OBJ and PLY frames (settings.output.formats): after a run, the last frame's files hold the
// World's final state: the cloth's OBJ vertices are its particle positions to the 9 significant
// digits OBJ is written with, the rigid box's OBJ vertices centre on the body's position, and the
// water's PLY holds every particle's position, velocity and density bit for bit. Blender's import
// of the same files is tested in tests/external/test_blender_import.py.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "moreau/moreau.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr const char* kScene = R"({"name": "formats", "settings": {"dt": 0.01, "duration": 0.05,
    "output": {"formats": ["vtk", "obj", "ply"]}},
  "objects": [
    {"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [0.6, 0.6], "resolution": [8, 8], "center": [0, 0.6, 0]},
     "material": {"area_density": 0.1}},
    {"name": "crate", "kind": "rigid_body", "shape": {"type": "box", "size": [0.3, 0.3, 0.3]}, "position": [-0.7, 0.3, 0]},
    {"name": "water", "kind": "fluid", "particle_radius": 0.02, "block": {"min": [0.5, 0.1, -0.1], "max": [0.7, 0.3, 0.1]}}]})";

struct ObjFile {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> faces;
};

ObjFile read_obj(const std::string& path) {
  std::ifstream in(path);
  ObjFile obj;
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line.substr(std::min<size_t>(2, line.size())));
    if (line.starts_with("v ")) obj.vertices.push_back({}), s >> obj.vertices.back()[0] >> obj.vertices.back()[1] >> obj.vertices.back()[2];
    if (line.starts_with("f ")) obj.faces.push_back({}), s >> obj.faces.back()[0] >> obj.faces.back()[1] >> obj.faces.back()[2];
  }
  return obj;
}

struct PlyFile {
  std::vector<std::string> properties;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(const std::string& name) const {
    const auto at = std::find(properties.begin(), properties.end(), name) - properties.begin();
    std::vector<double> values;
    for (const auto& row : rows) values.push_back(row.at(at));
    return values;
  }
};

PlyFile read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t end = file.find("end_header\n") + std::strlen("end_header\n");
  std::istringstream header(file.substr(0, end));
  PlyFile ply;
  size_t count = 0;
  for (std::string word; header >> word;) {
    if (word == "vertex") header >> count;
    if (word == "property") {
      std::string type, name;
      header >> type >> name;
      EXPECT_EQ(type, "double");
      ply.properties.push_back(name);
    }
  }
  EXPECT_EQ(file.size() - end, count * ply.properties.size() * sizeof(double)) << path;
  for (size_t i = 0; i < count; ++i) {
    ply.rows.emplace_back(ply.properties.size());
    std::memcpy(ply.rows.back().data(), file.data() + end + i * ply.properties.size() * sizeof(double),
                ply.properties.size() * sizeof(double));
  }
  return ply;
}

TEST(FrameFormats, ObjAndPlyFramesHoldTheFinalState) {
  const std::string out = test::temp_dir("frame-formats");
  World world = World::from_json(kScene);
  RunOptions options;
  options.out_dir = out;
  world.run(options);
  const std::string last = out + "/frames/";  // frame 5: after the 5th step
  ASSERT_FALSE(std::filesystem::exists(last + "sheet_000005.ply")) << "a surface gets no PLY";
  ASSERT_FALSE(std::filesystem::exists(last + "water_000005.obj")) << "a point set gets no OBJ";

  const ObjFile sheet = read_obj(last + "sheet_000005.obj");
  const StateArray x = world.array("particle.position");
  ASSERT_EQ(sheet.vertices.size(), static_cast<size_t>(x.count));
  EXPECT_EQ(sheet.faces.size(), 2u * 7 * 7);
  for (long i = 0; i < x.count; ++i)
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(sheet.vertices[i][d], x.values[3 * i + d], 1e-9) << "vertex " << i;
  for (const auto& f : sheet.faces)
    for (int v : f) EXPECT_TRUE(v >= 1 && v <= x.count);

  const ObjFile crate = read_obj(last + "crate_000005.obj");
  ASSERT_EQ(crate.vertices.size(), 8u);
  EXPECT_EQ(crate.faces.size(), 12u);
  const StateArray body = world.array("body.position");
  for (int d = 0; d < 3; ++d) {
    double centre = 0;
    for (const auto& v : crate.vertices) centre += v[d] / 8;
    EXPECT_NEAR(centre, body.values[d], 1e-8);
  }

  const PlyFile water = read_ply(last + "water_000005.ply");
  const StateArray position = world.array("fluid.position"), velocity = world.array("fluid.velocity");
  const StateArray density = world.array("fluid.density");
  ASSERT_EQ(water.rows.size(), static_cast<size_t>(position.count));
  ASSERT_EQ(position.count, 125);
  const char* axes[] = {"x", "y", "z"};
  for (int d = 0; d < 3; ++d) {
    const std::vector<double> p = water.column(axes[d]), v = water.column(std::string("velocity_") + axes[d]);
    for (long i = 0; i < position.count; ++i) {
      EXPECT_EQ(p[i], position.values[3 * i + d]);
      EXPECT_EQ(v[i], velocity.values[3 * i + d]);
    }
  }
  const std::vector<double> rho = water.column("density"), radius = water.column("radius");
  for (long i = 0; i < density.count; ++i) {
    EXPECT_EQ(rho[i], density.values[i]);
    EXPECT_EQ(radius[i], 0.02);
  }
}

TEST(FrameFormats, WithoutVtkThereIsNoPvdButRigidPosesRemain) {
  const std::string out = test::temp_dir("frame-formats-obj");
  World world = World::from_json(kScene, {"settings.output.formats=[\"obj\"]"});
  RunOptions options;
  options.out_dir = out;
  world.run(options);
  EXPECT_FALSE(std::filesystem::exists(out + "/formats.pvd"));
  EXPECT_TRUE(std::filesystem::exists(out + "/rigid_poses.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/frames/sheet_000005.obj"));
  EXPECT_FALSE(std::filesystem::exists(out + "/frames/sheet_000005.vtu"));
  EXPECT_FALSE(std::filesystem::exists(out + "/frames/water_000005.ply"));
}

// Σ x₀ · (x₁ × x₂) / 6 over the triangles: the enclosed volume, negative when they face inward.
double signed_volume(const ObjFile& obj) {
  double volume = 0;
  for (const auto& f : obj.faces) {
    const auto& a = obj.vertices[f[0] - 1];
    const auto& b = obj.vertices[f[1] - 1];
    const auto& c = obj.vertices[f[2] - 1];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
  }
  return volume;
}

TEST(FrameFormats, ContainerTrianglesFaceInwardAndSolidTrianglesOutward) {
  // A tank (an `inside` box) faces its contents, so a viewer culling back faces sees into it; a
  // solid box collider and a rigid box face out. Their volumes: 1 x 0.6 x 0.4 = 0.24 m³ and 0.3³.
  const std::string out = test::temp_dir("frame-formats-tank");
  World world = World::from_json(R"({"name": "tank", "settings": {"dt": 0.01, "duration": 0.01,
      "output": {"formats": ["obj"]}},
    "objects": [
      {"name": "tank", "kind": "collider", "inside": true, "shape": {"type": "box", "center": [0, 0.3, 0], "half_extents": [0.5, 0.3, 0.2]}},
      {"name": "block", "kind": "collider", "shape": {"type": "box", "center": [0.2, 0.1, 0], "half_extents": [0.05, 0.05, 0.05]}},
      {"name": "crate", "kind": "rigid_body", "shape": {"type": "box", "size": [0.3, 0.3, 0.3]}, "position": [-0.2, 0.2, 0]}]})");
  RunOptions options;
  options.out_dir = out;
  world.run(options);
  EXPECT_NEAR(signed_volume(read_obj(out + "/frames/tank_000001.obj")), -0.24, 1e-7);
  EXPECT_NEAR(signed_volume(read_obj(out + "/frames/block_000001.obj")), 1e-3, 1e-9);
  EXPECT_NEAR(signed_volume(read_obj(out + "/frames/crate_000001.obj")), 0.027, 1e-7);
}

}  // namespace
}  // namespace moreau
