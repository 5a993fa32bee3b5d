// libFuzzer target: the Wavefront OBJ reader (tinyobjloader behind read_obj_triangles) and the
// checks a closed surface gets. Refusals are InputError; anything else is a finding.
#include <cstdint>

#include "fuzz_input_file.hpp"
#include "moreau/errors.hpp"
#include "moreau/geometry/mesh_readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = moreau::fuzz::input_file(data, size, "mesh", ".obj");
  try {
    moreau::read_obj_triangles(path);
  } catch (const moreau::InputError&) {
  }
  return 0;
}
