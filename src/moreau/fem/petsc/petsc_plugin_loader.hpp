#pragma once
// Finds and loads the PETSc plugin (libmoreau_petsc.so) the first time a scene asks for it.
#include <string>

#include "moreau/fem/petsc/petsc_plugin_api.hpp"

namespace moreau {

/// The PETSc backend, loaded and initialized on the first call. Looked for in the file
/// $MOREAU_PETSC_PLUGIN names, if it is set (and nowhere else then); otherwise next to the running
/// program, in ../lib/moreau beside it, and in the build tree the engine was built in, in that
/// order. Throws std::runtime_error saying where it looked and why
/// loading failed.
petsc_plugin::Backend& petsc_backend();

}  // namespace moreau
