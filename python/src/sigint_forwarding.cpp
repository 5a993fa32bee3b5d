#include "sigint_forwarding.hpp"

#include <pybind11/pybind11.h>

#include "moreau/world.hpp"

namespace py = pybind11;

namespace moreau::python {
namespace {

extern "C" void stop_run_after_step(int signal_number) { moreau::request_stop(signal_number); }

bool on_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace

SigintForwarding::SigintForwarding() {
  if (!on_main_thread()) return;
  struct sigaction forward {};
  forward.sa_handler = stop_run_after_step;
  sigemptyset(&forward.sa_mask);
  installed_ = sigaction(SIGINT, &forward, &previous_) == 0;
}

SigintForwarding::~SigintForwarding() {
  if (installed_) sigaction(SIGINT, &previous_, nullptr);
}

}  // namespace moreau::python
