// The Python module `moreau._moreau` (re-exported by the package `moreau`, python/moreau/): the
// C++ World (include/moreau/world.hpp) with its state as numpy arrays, and moreau's two error
// tiers as Python exceptions.
#include <pybind11/pybind11.h>

#include "moreau/moreau.hpp"
#include "python_bindings.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_moreau, m) {
  m.doc() = "moreau: a multiphysics simulation engine (compiled core; see the package moreau).";
  moreau::python::bind_errors(m);
  moreau::python::bind_world(m);
  m.def("version", &moreau::version, "The engine's version string, e.g. '0.1.0'.");
  m.def("set_memory_limit", &moreau::set_memory_limit, py::arg("bytes"),
        "The memory (bytes) a scene's meshes and particles may need, checked when a scene is loaded;\n"
        "a larger scene raises InputError naming the key. Default: 80 % of the physical memory.");
}
