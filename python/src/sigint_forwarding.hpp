#pragma once
// Ctrl-C during World.run: while a run holds no GIL, Python's own SIGINT handler would only set a
// flag that nobody reads until the run ends. For the lifetime of this guard, SIGINT instead asks
// the run to stop after its current step and write a checkpoint (moreau::request_stop), as the
// command line does; the previous handler comes back afterwards. Only on Python's main thread,
// where Python itself handles signals; elsewhere the guard does nothing.
#include <csignal>

namespace moreau::python {

class SigintForwarding {
 public:
  SigintForwarding();  // needs the GIL
  ~SigintForwarding();
  SigintForwarding(const SigintForwarding&) = delete;
  SigintForwarding& operator=(const SigintForwarding&) = delete;

 private:
  bool installed_ = false;
  struct sigaction previous_ {};
};

}  // namespace moreau::python
