// moreau's error tiers as Python exceptions. Bad input is a ValueError (the command line's exit
// code 2), numerical failure a RuntimeError (exit code 3); both carry the C++ message unchanged.
#include <pybind11/pybind11.h>

#include "moreau/errors.hpp"
#include "python_bindings.hpp"

namespace py = pybind11;

namespace moreau::python {

void bind_errors(py::module_& m) {
  auto& input_error = py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  input_error.attr("__doc__") =
      "A scene, mesh or parameter is not valid. The message names the file (or '(scene JSON)'), the\n"
      "JSON path and what is allowed. Nothing was written.";
  auto& numerical_error = py::register_exception<NumericalError>(m, "NumericalError", PyExc_RuntimeError);
  numerical_error.attr("__doc__") =
      "The simulation diverged. The message names the step, the simulated time and the object; the\n"
      "state is what the failed step left (to inspect, not to continue from).";
}

}  // namespace moreau::python
