// Bad rod input is an InputError naming the JSON path, what is wrong and what is allowed.
#include <gtest/gtest.h>

#include <string>

#include "moreau/errors.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

std::string scene(const std::string& rod_keys, const std::string& extra = "") {
  return R"({"name": "bad", "objects": [{"name": "rope", "kind": "rod", )" + rod_keys + "}]" + extra + "}";
}

// The message of the InputError that loading `json` throws ("" if it loads).
std::string error_of(const std::string& json) {
  try {
    World::from_json(json);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& json, const std::string& path, const std::string& words) {
  const std::string message = error_of(json);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find(words), std::string::npos) << message;
}

const std::string kGood = R"("points": [[0, 1, 0], [1, 1, 0]], "radius": 0.01, "youngs_modulus": 1e9)";

TEST(RodSceneErrors, EachBadKeyIsNamedWithWhatIsAllowed) {
  EXPECT_EQ(error_of(scene(kGood)), "");
  expect_error(scene(R"("points": [[0, 1, 0], [1, 1, 0]], "radius": 0.01, "radii": [0.01, 0.02], "youngs_modulus": 1e9)"),
               "objects[0].radius", "exactly one of");
  expect_error(scene(R"("points": [[0, 1, 0], [1, 1, 0]], "radius": 0.01)"), "objects[0].youngs_modulus", "missing");
  expect_error(scene(R"("points": [[0, 1, 0], [1, 1, 0]], "radius": -0.01, "youngs_modulus": 1e9)"), "objects[0].radius",
               "out of range");
  expect_error(scene(kGood + R"(, "start": "glued")"), "objects[0].start", "clamped");
  expect_error(scene(R"("points": [[0, 1, 0]], "radius": 0.01, "youngs_modulus": 1e9)"), "objects[0].points",
               "at least two points");
  expect_error(scene(R"("points": [[0, 1, 0], [0, 1, 0]], "radius": 0.01, "youngs_modulus": 1e9)"), "objects[0].points",
               "coincide");
  expect_error(scene(kGood + R"(, "segments": 0)"), "objects[0].segments", "out of range");
  expect_error(scene(kGood + R"(, "poisson_ratio": 0.5)"), "objects[0].poisson_ratio", "out of range");
  expect_error(scene(kGood + R"(, "damping": 1)"), "objects[0].damping", "damping_time");
  expect_error(scene(kGood, R"(, "joints": [{"name": "j", "type": "spherical", "bodies": ["world", "rope"], "anchor": [0, 1, 0]}])"),
               "joints[0].bodies", "vertex");
  expect_error(scene(kGood, R"(, "joints": [{"name": "j", "type": "spherical", "bodies": ["world", {"object": "rope", "vertex": 2}]}])"),
               "joints[0].bodies[1].vertex", "out of range");
  expect_error(scene(kGood, R"(, "probes": [{"name": "t", "type": "twist", "object": "nothing"}])"), "probes[0].object",
               "rope");
}

}  // namespace
}  // namespace moreau
