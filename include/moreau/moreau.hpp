#pragma once
// The public C++ API of moreau: load a scene (a file or JSON text) into a World, inspect it, step
// it, read and write its state, or run it to an output directory (world.hpp); or build a scene
// in code, object by object (scene_builder.hpp); or run one scene under several solvers side by
// side (compare.hpp).
#include "moreau/compare.hpp"
#include "moreau/errors.hpp"
#include "moreau/scene_builder.hpp"
#include "moreau/world.hpp"

namespace moreau {

/// The version string, e.g. "0.1.0".
const char* version();

/// The memory a scene's meshes and particles may need, in bytes, checked when a scene is loaded
/// (a larger scene is an InputError naming the key). Default: 80 % of the physical memory.
void set_memory_limit(double bytes);

}  // namespace moreau
