// The catalogue of bad input: every entry is a scene (with files beside it) or a command line a
// user could get wrong, run through `moreau run`. Each must exit with code 2, name where the
// problem is (the file and JSON path, the flag or the file) and what is allowed, and write
// nothing: the output directory must not exist afterwards. Entries: malformed JSON, unknown and
// misspelt keys (with the closest allowed key suggested), wrong types, values out of range, NaN
// and infinities, missing, empty, garbage and inverted meshes (OBJ, TetGen, Gmsh), a directory
// where a file should be, an output place that cannot be written, bad flags and --set paths, and
// checkpoints that do not belong to the scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

// A valid cloth scene; entries replace FIELD with their own text.
constexpr const char* kCloth = R"({"name": "cat", "settings": {"dt": 0.01, "duration": 0.05},
  "objects": [{"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [1, 1], "resolution": [4, 4]},
               "material": {"area_density": 0.1}}FIELD]})";

// A soft body whose mesh is the file `mesh` (type `type`) beside the scene.
std::string soft_body(const std::string& type, const std::string& mesh) {
  return fmt::format(R"({{"name": "cat", "objects": [{{"name": "blob", "kind": "soft_body", "mesh": {{"type": "{}", "file": "{}"}},
    "material": {{"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}}}]}})",
                     type, mesh);
}

std::string cloth_with(const std::string& field) {
  std::string text = kCloth;
  return text.replace(text.find("FIELD"), 5, field);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

struct BadInput {
  const char* name;
  std::string scene;                                   // the scene file's text
  std::vector<std::pair<std::string, std::string>> files;  // other files beside it: name, text ("/" ending: a directory)
  std::string args;                                    // more arguments ({dir}: the scene's directory)
  std::vector<std::string> expected;                   // what the message must contain
};

std::vector<BadInput> catalogue() {
  const std::string cloth = cloth_with("");
  const std::string cube_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  return {
      // The JSON itself.
      {"malformed_json", "{\"name\": \"cat\", \"objects\": [,]}", {}, "", {"scene.json:1:", "malformed JSON"}},
      {"empty_file", "", {}, "", {"scene.json", "malformed JSON"}},
      {"not_an_object", "[1, 2, 3]", {}, "", {"scene.json", "object"}},
      {"duplicate_key", replaced(cloth, "\"duration\": 0.05", "\"dt\": 0.02, \"duration\": 0.05"), {}, "", {"settings.dt", "duplicate"}},
      // Keys.
      {"unknown_top_key", replaced(cloth, "\"objects\"", "\"probez\": [], \"objects\""), {}, "", {"probez", "unknown key", "probes"}},
      {"misspelt_setting", replaced(cloth, "\"duration\"", "\"durration\""), {}, "", {"settings.durration", "did you mean 'duration'"}},
      {"misspelt_material_key", replaced(cloth, "\"area_density\"", "\"area_densty\""), {}, "",
       {"objects[0].material.area_densty", "area_density"}},
      {"unknown_kind", replaced(cloth, "\"cloth\"", "\"clothes\""), {}, "", {"objects[0].kind", "cloth"}},
      {"missing_required_key", replaced(cloth, "\"name\": \"sheet\", ", ""), {}, "", {"objects[0].name", "required"}},
      // Types and ranges.
      {"wrong_type", replaced(cloth, "0.01", "\"fast\""), {}, "", {"settings.dt", "expected a number"}},
      {"negative_dt", replaced(cloth, "0.01", "-1"), {}, "", {"settings.dt", "out of range"}},
      {"zero_density", replaced(cloth, "\"area_density\": 0.1", "\"area_density\": 0"), {}, "", {"area_density", "out of range"}},
      {"vector_of_two", replaced(cloth, "\"size\": [1, 1]", "\"size\": [1]"), {}, "", {"objects[0].mesh.size"}},
      {"huge_number", replaced(cloth, "0.01", "1e999"), {}, "", {"settings.dt", "'1e999' does not fit a double"}},
      {"nan_by_set", cloth, {}, "--set settings.dt=nan", {"settings.dt"}},
      {"infinity_by_set", cloth, {}, "--set settings.gravity=[0,-inf,0]", {"settings.gravity"}},
      {"unknown_frame_format", cloth, {}, "--set 'settings.output.formats=[\"vtk\",\"stl\"]'",
       {"settings.output.formats", "\"stl\" is not a known format; allowed: vtk, obj, ply"}},
      {"too_many_vertices", replaced(cloth, "[4, 4]", "[100000, 100000]"), {}, "", {"objects[0].mesh.resolution", "memory limit"}},
      // Mesh files.
      {"missing_obj", soft_body("obj", "nowhere.obj"), {}, "", {"objects[0].mesh.file", "nowhere.obj", "not found"}},
      {"empty_obj", soft_body("obj", "empty.obj"), {{"empty.obj", ""}}, "", {"empty.obj"}},
      {"garbage_obj", soft_body("obj", "garbage.obj"), {{"garbage.obj", "v 1 2\nf a b c\n\x01\x02 binary junk\n"}}, "", {"garbage.obj"}},
      {"open_surface_obj", soft_body("obj", "open.obj"), {{"open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"}}, "", {"open.obj"}},
      {"directory_as_mesh", soft_body("obj", "meshdir"), {{"meshdir/", ""}}, "", {"meshdir"}},
      {"missing_tetgen", soft_body("tetgen", "nothing"), {}, "", {"nothing", "cannot open"}},
      {"garbage_tetgen", soft_body("tetgen", "junk"), {{"junk.node", "three nodes\n"}, {"junk.ele", "1 4 0\n0 0 1 2 3\n"}}, "",
       {"junk.node"}},
      {"tetgen_index_out_of_range", soft_body("tetgen", "far"),
       {{"far.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n"}, {"far.ele", "1 4 0\n0 0 1 2 9\n"}}, "", {"far.ele"}},
      {"inverted_tetrahedra", soft_body("tetgen", "inv"),
       {{"inv.node", "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n"}, {"inv.ele", "2 4 0\n0 0 1 2 3\n1 1 3 2 4\n"}}, "",
       {"inverted"}},
      {"garbage_gmsh", soft_body("msh", "junk.msh"), {{"junk.msh", "$MeshFormat\nnot a version\n$EndMeshFormat\n"}}, "", {"junk.msh"}},
      {"obj_for_cube_ok_but_scene_dir", soft_body("obj", "cube.obj"), {{"cube.obj", cube_obj}}, "--out {dir}/scene.json",
       {"--out", "not a directory"}},
      // Paths and flags.
      {"scene_is_a_directory", "", {}, "SCENE_DIR", {"is a directory"}},
      {"unwritable_output", cloth, {}, "--out /proc/moreau-out", {"--out /proc/moreau-out"}},
      {"unknown_set_path", cloth, {}, "--set settings.substepz=4", {"settings.substepz", "substeps"}},
      {"set_without_value", cloth, {}, "--set settings.dt", {"settings.dt"}},
      {"set_index_too_long", cloth, {}, "--set objects.123456789012345678901234567890.name=x",
       {"objects.123456789012345678901234567890", "no element"}},
      {"threads_out_of_range", cloth, {}, "--threads 5000", {"--threads", "not in range"}},
      {"negative_duration", cloth, {}, "--duration -1", {"--duration"}},
      {"restart_missing", cloth, {}, "--restart {dir}/none.bin", {"--restart", "none.bin", "cannot open"}},
      {"restart_not_a_checkpoint", cloth, {{"fake.bin", "not a checkpoint"}}, "--restart {dir}/fake.bin",
       {"--restart", "fake.bin", "not a moreau checkpoint"}},
  };
}

class BadInputCatalogue : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputCatalogue, ExitsTwoNamingWhereAndWritesNothing) {
  const BadInput& c = GetParam();
  const std::string dir = test::temp_dir(std::string("bad-input-") + c.name);
  std::ofstream(dir + "/scene.json") << c.scene;
  for (const auto& [name, text] : c.files) {
    if (name.ends_with("/")) fs::create_directories(dir + "/" + name);
    else std::ofstream(dir + "/" + name, std::ios::binary) << text;
  }
  std::string args = c.args;
  for (size_t at; (at = args.find("{dir}")) != std::string::npos;) args.replace(at, 5, dir);
  std::string scene = dir + "/scene.json";
  if (args == "SCENE_DIR") {
    scene = dir;
    args.clear();
  }
  const std::string out = args.find("--out") == std::string::npos ? dir + "/out" : "";
  const test::CommandResult r =
      test::run_moreau(fmt::format("run {} {} --quiet {}", scene, out.empty() ? "" : "--out " + out, args));
  EXPECT_EQ(r.exit_code, 2) << c.name << "\n" << r.output;
  for (const std::string& what : c.expected) EXPECT_NE(r.output.find(what), std::string::npos) << c.name << ": " << what << "\n" << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
  if (!out.empty()) {
    EXPECT_FALSE(fs::exists(out)) << c.name << ": the refused run wrote " << out;
  }
}

INSTANTIATE_TEST_SUITE_P(Inputs, BadInputCatalogue, ::testing::ValuesIn(catalogue()),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace moreau
