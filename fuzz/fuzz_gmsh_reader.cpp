// libFuzzer target: the Gmsh MSH 4.1 ASCII readers, for soft-body tetrahedra and for FEM meshes
// (tetrahedra, hexahedra, triangles, quadrilaterals and their physical groups). Refusals are
// InputError; anything else is a finding.
#include <cstdint>

#include "fuzz_input_file.hpp"
#include "moreau/errors.hpp"
#include "moreau/fem/core/fem_mesh.hpp"
#include "moreau/geometry/mesh_readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = moreau::fuzz::input_file(data, size, "mesh", ".msh");
  try {
    moreau::TetMesh tets = moreau::read_gmsh_msh4(path);
    moreau::orient_and_validate_tets(tets, path);
  } catch (const moreau::InputError&) {
  }
  try {
    moreau::read_gmsh_fem_mesh(path);
  } catch (const moreau::InputError&) {
  }
  return 0;
}
