// libFuzzer target: the --set override parser ("path=value" applied to a scene's JSON). The
// input's first line is the assignment, the rest the scene JSON it applies to (a small valid
// scene when the rest is empty). Refusals are InputError; anything else is a finding.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "moreau/errors.hpp"
#include "moreau/scene/json_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t newline = text.find('\n');
  const std::string assignment = text.substr(0, newline);
  const std::string scene_text = newline == std::string::npos ? "" : text.substr(newline + 1);
  try {
    nlohmann::json scene = scene_text.empty()
                               ? nlohmann::json::parse(R"({"name": "s", "settings": {"dt": 0.01, "output": {"every": 2}},
                                   "objects": [{"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [1, 1]}}]})")
                               : moreau::parse_json_text(scene_text, "fuzz.json");
    moreau::apply_override(scene, assignment, "fuzz.json");
  } catch (const moreau::InputError&) {
  }
  return 0;
}
