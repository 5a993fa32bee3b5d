// SceneBuilder (include/moreau/scene_builder.hpp): a scene built in code is the scene its file
// describes, bit for bit; meshes given in code equal the generated ones; a body built in code
// falls as the integrator's closed form says; and bad specs are InputErrors naming the scene, the
// entry and the field.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "moreau/geometry/mesh_generators.hpp"
#include "moreau/moreau.hpp"

namespace moreau::test {
namespace {

std::string repository_scene(const char* name) {
  return (std::filesystem::path(MOREAU_SOURCE_DIR) / "scenes" / name).string();
}

// Every state array and probe value of the two worlds, compared bit for bit.
void expect_identical(World& a, World& b) {
  const auto arrays_a = a.arrays(), arrays_b = b.arrays();
  ASSERT_EQ(arrays_a.size(), arrays_b.size());
  for (size_t k = 0; k < arrays_a.size(); ++k) {
    SCOPED_TRACE(arrays_a[k].name);
    ASSERT_EQ(arrays_a[k].name, arrays_b[k].name);
    ASSERT_EQ(arrays_a[k].values.size(), arrays_b[k].values.size());
    // (memcmp of an empty array's null data would be undefined: compare only what there is)
    if (!arrays_a[k].values.empty()) {
      EXPECT_EQ(std::memcmp(arrays_a[k].values.data(), arrays_b[k].values.data(), arrays_a[k].values.size() * sizeof(double)), 0);
    }
  }
  EXPECT_EQ(a.probe_names(), b.probe_names());
  const auto pa = a.probe_values(), pb = b.probe_values();
  ASSERT_EQ(pa.size(), pb.size());
  for (size_t k = 0; k < pa.size(); ++k)
    EXPECT_TRUE(pa[k] == pb[k] || (std::isnan(pa[k]) && std::isnan(pb[k]))) << a.probe_names()[k];
}

void step_both(World& a, World& b, int steps) {
  for (int s = 0; s < steps; ++s) {
    a.step(1);
    b.step(1);
  }
}

// scenes/rope_bridge.json, spec by spec: planks hinged to each other and to the world, fixed
// posts, a soft cube thrown onto them, and its probes.
SceneBuilder rope_bridge() {
  SceneBuilder scene("rope_bridge");
  scene.settings().dt = 0.016666666666666666;
  scene.settings().substeps = 20;
  scene.settings().duration = 5.0;
  scene.add(ColliderSpec{.name = "ground", .contact = {.static_friction = 0.6, .dynamic_friction = 0.6}});
  for (double x : {-0.1, 3.6999999999999997})
    scene.add(RigidBodySpec{.name = x < 0 ? "post_left" : "post_right",
                            .shape = BoxShape{{0.1, 0.7, 0.6}},
                            .fixed = true,
                            .position = Vector3{x, 0.7, 0}});
  // The file's numbers to the last bit (its generator summed 0.3 m steps).
  const double plank_x[12] = {0.15, 0.44999999999999996, 0.75, 1.05, 1.3499999999999999, 1.65, 1.95, 2.25, 2.55,
                              2.85, 3.15, 3.4499999999999997};
  for (int k = 0; k < 12; ++k)
    scene.add(RigidBodySpec{.name = "plank" + std::to_string(k),
                            .shape = BoxShape{{0.145, 0.02, 0.5}},
                            .density = 500,
                            .position = Vector3{plank_x[k], 1.5, 0},
                            .contact = {.static_friction = 0.6, .dynamic_friction = 0.6}});
  SoftBodySpec jelly{.name = "jelly",
                     .mesh = TetBox{.min = {0.3, 1.55, -0.15}, .max = {0.6, 1.85, 0.15}, .cells = {4, 4, 4}},
                     .material = {.youngs_modulus = 40000.0, .poisson_ratio = 0.35, .density = 300, .damping = 0.002},
                     .velocity = {2.0, 0, 0},
                     .contact = {.static_friction = 0.1, .dynamic_friction = 0.1}};
  scene.add(jelly);
  const double anchor_x[13] = {0.0, 0.3, 0.6, 0.8999999999999999, 1.2, 1.5, 1.7999999999999998, 2.1, 2.4,
                               2.6999999999999997, 3.0, 3.3, 3.5999999999999996};
  for (int k = 0; k <= 12; ++k) {
    JointSpec hinge{.name = "hinge" + std::to_string(k), .type = "hinge"};
    hinge.bodies[0].object = k == 0 ? "world" : "plank" + std::to_string(k - 1);
    hinge.bodies[1].object = k == 12 ? "world" : "plank" + std::to_string(k);
    hinge.anchor = Vector3{anchor_x[k], 1.5, 0};
    hinge.axis = {0, 0, 1};
    hinge.compliance = 1e-07;
    scene.add(hinge);
  }
  scene.add(ProbeSpec{.name = "jelly", .type = "center_of_mass", .object = "jelly"});
  scene.add(ProbeSpec{.name = "mid_plank", .type = "position", .object = "plank6"});
  scene.add(ProbeSpec{.name = "hinges", .type = "joint_error", .joint = "*"});
  scene.add(ProbeSpec{.name = "jelly_contacts", .type = "contact_count", .object = "jelly"});
  return scene;
}

TEST(SceneBuilder, BuildsTheRopeBridgeItsSceneFileDescribes) {
  World from_file = World::load(repository_scene("rope_bridge.json"));
  World in_code = rope_bridge().build();
  EXPECT_EQ(in_code.summary().substr(in_code.summary().find(':')), from_file.summary().substr(from_file.summary().find(':')))
      << "the same objects, bodies, joints and constraints";
  step_both(from_file, in_code, 60);  // 1 s: the cube lands on the planks
  expect_identical(from_file, in_code);
}

// scenes/hammock_pour.json: a pinned cloth, a disc emitter, a plane given by its offset.
TEST(SceneBuilder, BuildsTheHammockPourItsSceneFileDescribes) {
  SceneBuilder scene("hammock_pour");
  scene.settings().dt = 0.004;
  scene.settings().substeps = 8;
  scene.settings().iterations = 1;
  scene.settings().duration = 4.0;
  scene.settings().output_every = 5;
  scene.add(ColliderSpec{.name = "floor", .shape = PlaneShape{.normal = {0, 1, 0}, .point = {0, 0, 0}}});
  ClothSpec hammock{.name = "hammock",
                    .mesh = GridSheet{.size = {0.6, 0.6}, .resolution = {31, 31}, .center = {0, 1.0, 0}},
                    .material = {.area_density = 0.4, .damping = 0.002, .stretch_compliance = 3e-3, .bending_stiffness = 1e-5}};
  for (auto [lo, hi] : {std::pair<Vector3, Vector3>{{-1, 0.9, -1}, {-0.299, 1.1, 1}},
                        {{0.299, 0.9, -1}, {1, 1.1, 1}},
                        {{-1, 0.9, -1}, {1, 1.1, -0.299}},
                        {{-1, 0.9, 0.299}, {1, 1.1, 1}}})
    hammock.pin.push_back(PinSpec{.region = PinBox{lo, hi}});
  scene.add(hammock);
  scene.add(FluidSpec{.name = "water",
                      .particle_radius = 0.0075,
                      .emitter = FluidEmitterSpec{.shape = "disc", .center = {0, 0.97, 0}, .direction = {0, -1, 0},
                                                  .radius = 0.03, .speed = 0.5, .start = 0.6, .stop = 3.0}});
  scene.add(ProbeSpec{.name = "water_particles", .type = "particle_count", .object = "water"});
  scene.add(ProbeSpec{.name = "hammock_lowest", .type = "extent", .object = "hammock", .quantity = "min", .axis = "y"});
  scene.add(ProbeSpec{.name = "water_lowest", .type = "extent", .object = "water", .quantity = "min", .axis = "y"});
  scene.add(ProbeSpec{.name = "density_error", .type = "density_error", .object = "water"});
  World in_code = scene.build();
  World from_file = World::load(repository_scene("hammock_pour.json"));
  step_both(from_file, in_code, 200);  // 0.8 s: the emitter has run for 0.2 s
  EXPECT_GT(in_code.array("fluid.position").count, 50);
  expect_identical(from_file, in_code);
}

// A cloth and a soft body whose meshes are given in code equal those the generators make.
TEST(SceneBuilder, MeshesGivenInCodeEqualTheGeneratedOnes) {
  const TriangleMesh sheet = make_grid_sheet(Vec2(0.4, 0.3), {5, 4}, Vec3(0, 1, 0));
  TriangleList triangles;
  for (const Vec3& v : sheet.vertices) triangles.vertices.push_back({v.x(), v.y(), v.z()});
  for (const auto& t : sheet.triangles) triangles.triangles.push_back({t[0], t[1], t[2]});
  const TetMesh block = make_box_tets(Vec3(1, 0.5, 0), Vec3(1.2, 0.7, 0.3), {2, 2, 3}, CellSplit::six);
  TetList tets;
  for (const Vec3& v : block.vertices) tets.vertices.push_back({v.x(), v.y(), v.z()});
  for (const auto& t : block.tets) tets.tets.push_back({t[0], t[1], t[2], t[3]});

  auto build = [&](ClothMesh cloth_mesh, SoftBodyMesh soft_mesh) {
    SceneBuilder scene("meshes");
    scene.add(ColliderSpec{.name = "floor"});
    scene.add(ClothSpec{.name = "sheet", .mesh = std::move(cloth_mesh), .material = {.area_density = 0.2, .bend_compliance = 1e-3}});
    scene.add(SoftBodySpec{.name = "block", .mesh = std::move(soft_mesh),
                           .material = {.youngs_modulus = 1e5, .poisson_ratio = 0.3, .density = 800}});
    return scene.build();
  };
  World generated = build(GridSheet{.size = {0.4, 0.3}, .resolution = {5, 4}, .center = {0, 1, 0}},
                          TetBox{.min = {1, 0.5, 0}, .max = {1.2, 0.7, 0.3}, .cells = {2, 2, 3}});
  World given = build(triangles, tets);
  step_both(generated, given, 30);
  expect_identical(generated, given);
}

// With gravity only, the position integrator (v += g h, x += v h per substep h = dt / n) puts a
// body released at rest at y0 - g h^2 N (N + 1) / 2 after N substeps: exact up to round-off.
TEST(SceneBuilder, ABodyBuiltInCodeFallsAsTheIntegratorsClosedFormSays) {
  SceneBuilder scene("drop");
  scene.settings().dt = 0.01;
  scene.settings().substeps = 4;
  scene.add(RigidBodySpec{.name = "ball", .shape = SphereShape{0.05}, .mass = 0.2, .position = Vector3{0, 2, 0}});
  scene.add(ProbeSpec{.name = "ball", .type = "position", .object = "ball"});
  World world = scene.build();
  for (int s = 0; s < 50; ++s) world.step();
  const double h = 0.01 / 4, N = 200, g = 9.81;
  const double expected = 2 - g * h * h * N * (N + 1) / 2;  // 1.87714... m
  const std::vector<double> probe = world.probe_values();   // x, y, z of the centre
  ASSERT_EQ(probe.size(), 3u);
  EXPECT_NEAR(probe[1], expected, 1e-12);
  EXPECT_EQ(probe[0], 0.0);
}

std::string build_error(const SceneBuilder& scene) {
  try {
    scene.build();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneBuilder, BadSpecsNameTheSceneTheEntryAndTheField) {
  {
    SceneBuilder scene("bad");
    scene.add(ColliderSpec{.name = "floor"});
    scene.add(RigidBodySpec{.name = "box", .shape = BoxShape{{0.1, 0.1, 0.1}}, .mass = -1, .position = Vector3{0, 1, 0}});
    EXPECT_EQ(build_error(scene), "scene 'bad': objects[1].mass: -1 is out of range; allowed: > 0");
  }
  {
    SceneBuilder scene("bad");
    scene.add(RigidBodySpec{.name = "box", .shape = BoxShape{{0.1, 0.1, 0.1}}});
    EXPECT_EQ(build_error(scene), "scene 'bad': objects[0].position: missing required key");
  }
  {
    SceneBuilder scene("bad");
    scene.add(ColliderSpec{.name = "post", .shape = CylinderShape{0.1, 0.5}});
    EXPECT_NE(build_error(scene).find("objects[0].shape.type: a collider is a plane, box, sphere or capsule"), std::string::npos);
  }
  {
    SceneBuilder scene("bad");
    scene.add(ClothSpec{.name = "sheet",
                        .mesh = TriangleList{.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, .triangles = {{0, 1, 3}}},
                        .material = {.area_density = 0.1}});
    EXPECT_EQ(build_error(scene), "scene 'bad': objects[0].mesh.triangles: vertex 3 does not exist; the mesh has 3 vertices");
  }
  {
    SceneBuilder scene("bad");
    scene.add(RigidBodySpec{.name = "a", .shape = SphereShape{0.1}, .position = Vector3{0, 1, 0}});
    scene.add(RigidBodySpec{.name = "a", .shape = SphereShape{0.1}, .position = Vector3{0, 2, 0}});
    EXPECT_EQ(build_error(scene), "scene 'bad': objects[1].name: another object is already named 'a'; names must be unique");
  }
  {
    SceneBuilder scene("bad");
    scene.add(RigidBodySpec{.name = "a", .shape = SphereShape{0.1}, .position = Vector3{0, 1, 0}});
    JointSpec joint{.name = "j", .type = "hinge", .anchor = Vector3{0, 1, 0}, .limits = Vector2{0, 1}};
    joint.bodies[1].object = "a";
    scene.add(joint);
    EXPECT_EQ(build_error(scene), "scene 'bad': joints[0].limits: only a prismatic joint takes \"limits\"");
  }
  {
    SceneBuilder scene("bad");
    scene.add(RigidBodySpec{.name = "a", .shape = SphereShape{0.1}, .position = Vector3{0, 1, 0}});
    JointSpec joint{.name = "j", .type = "hinge", .anchor = Vector3{0, 1, 0}};
    joint.bodies[1].object = "b";
    scene.add(joint);
    EXPECT_NE(build_error(scene).find("joints[0].bodies: bodies[1] is 'b', which is not a rigid body of this scene"),
              std::string::npos);
  }
  {
    // Fields a shape does not take are refused, not ignored.
    SceneBuilder scene("bad");
    scene.add(ColliderSpec{.name = "floor", .shape = PlaneShape{}, .center = {0, 1, 0}});
    EXPECT_EQ(build_error(scene), "scene 'bad': objects[0].shape.center: a plane is placed by its \"point\" and \"normal\"");
  }
  {
    SceneBuilder scene("bad");
    scene.add(FluidSpec{.name = "water", .particle_radius = 0.01,
                        .emitter = FluidEmitterSpec{.shape = "disc", .direction = {0, -1, 0}, .radius = 0.05,
                                                    .size = {0.1, 0.1}, .speed = 1.0}});
    EXPECT_NE(build_error(scene).find("objects[0].emitter.size: a disc takes a \"radius\""), std::string::npos);
  }
  {
    SceneBuilder scene("bad");
    scene.settings().solver = "fem";
    scene.add(RigidBodySpec{.name = "a", .position = Vector3{0, 1, 0}});
    EXPECT_NE(build_error(scene).find("settings.solver: FEM scenes are read from scene JSON"), std::string::npos);
  }
  {
    SceneBuilder scene("bad");
    scene.settings().dt = std::nan("");
    scene.add(RigidBodySpec{.name = "a", .position = Vector3{0, 1, 0}});
    EXPECT_EQ(build_error(scene), "scene 'bad': settings.dt: nan is out of range; allowed: > 0");
  }
}

}  // namespace
}  // namespace moreau::test

namespace moreau {
namespace {

// The velocity-level settings set in code reach the model as the same keys in a file do: a
// pendulum whose joint is stiffened (the direct solve and d = 3.5) the same bits either way, and
// not the bits of the defaults.
TEST(SceneBuilder, NmdSettingsInCodeMatchTheFileKeys) {
  SceneBuilder scene("nmd");
  scene.settings().solver = "nmd";
  scene.settings().nmd.method = "hybrid";
  scene.settings().nmd.iterations = 7;
  scene.settings().nmd.stabilization = 3.5;
  scene.add(RigidBodySpec{.name = "ball", .shape = SphereShape{0.1}, .position = Vector3{1, 0, 0}});
  scene.add(JointSpec{.name = "pivot", .type = "spherical", .bodies = {JointEndSpec{}, JointEndSpec{.object = "ball"}},
                      .anchor = Vector3{0, 0, 0}});
  scene.add(ProbeSpec{.name = "ball", .type = "position", .object = "ball"});
  World in_code = scene.build();
  const std::string file = R"({"name": "nmd", "settings": {"solver": "nmd"NMD},
    "objects": [{"name": "ball", "kind": "rigid_body", "shape": {"type": "sphere", "radius": 0.1}, "position": [1, 0, 0]}],
    "joints": [{"name": "pivot", "type": "spherical", "bodies": ["world", "ball"], "anchor": [0, 0, 0]}],
    "probes": [{"name": "ball", "type": "position", "object": "ball"}]})";
  auto with = [&](const std::string& nmd) { return std::string(file).replace(file.find("NMD"), 3, nmd); };
  World from_file = World::from_json(with(R"(, "nmd": {"method": "hybrid", "iterations": 7, "stabilization": 3.5})"));
  World defaults = World::from_json(with(""));
  for (int s = 0; s < 30; ++s) {
    in_code.step(1);
    from_file.step(1);
    defaults.step(1);
  }
  EXPECT_EQ(in_code.probe_values(), from_file.probe_values());
  EXPECT_NE(in_code.probe_values(), defaults.probe_values());
  // Bad values name the setting as a file's path would.
  SceneBuilder bad("bad");
  bad.settings().solver = "nmd";
  bad.settings().nmd.method = "lcp";
  bad.add(RigidBodySpec{.name = "ball", .shape = SphereShape{0.1}});
  try {
    bad.build();
    ADD_FAILURE() << "an unknown method must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("settings.nmd.method"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace moreau
