#pragma once
// The parts of the Python module, each bound in its own file.
#include <pybind11/pybind11.h>

namespace moreau::python {

/// moreau.InputError (a ValueError) and moreau.NumericalError (a RuntimeError), raised with the
/// C++ message: the file, the JSON path and what is allowed; or the step, the time and the object.
void bind_errors(pybind11::module_& m);

/// moreau.World and moreau.WorldObject.
void bind_world(pybind11::module_& m);

}  // namespace moreau::python
