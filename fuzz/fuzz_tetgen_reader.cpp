// libFuzzer target: the TetGen reader (.node and .ele) and the orientation check of its
// tetrahedra. The input is the .node text, a line "%%", then the .ele text. Refusals are
// InputError; anything else is a finding.
#include <cstdint>
#include <string>

#include "fuzz_input_file.hpp"
#include "moreau/errors.hpp"
#include "moreau/geometry/mesh_readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find("\n%%\n");
  const std::string node = text.substr(0, split), ele = split == std::string::npos ? "" : text.substr(split + 4);
  const std::string node_path = moreau::fuzz::input_file(reinterpret_cast<const uint8_t*>(node.data()), node.size(), "mesh", ".node");
  const std::string ele_path = moreau::fuzz::input_file(reinterpret_cast<const uint8_t*>(ele.data()), ele.size(), "mesh", ".ele");
  try {
    moreau::TetMesh mesh = moreau::read_tetgen(node_path, ele_path);
    moreau::orient_and_validate_tets(mesh, node_path);
  } catch (const moreau::InputError&) {
  }
  return 0;
}
