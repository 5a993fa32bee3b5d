// The plugin's entry point: PETSc initialized once per process, and the solvers it makes.
#include <petscksp.h>

#include <cstdlib>

#include "krylov_solver.hpp"
#include "mpi_world.hpp"
#include "moreau/fem/petsc/petsc_plugin_api.hpp"
#include "petsc_call.hpp"

namespace moreau::petsc_plugin {
namespace {

class PetscBackend final : public Backend {
 public:
  PetscBackend() {
    // The engine has its own handlers for crashes and reports its own errors: PETSc keeps out of
    // both (no signal handler; an error returns its code instead of printing a traceback).
    petsc_call(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
    petsc_call(PetscInitializeNoArguments(), "PetscInitialize");
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    // Objects still alive at exit (a run stopped by an error) are left to the operating system.
    std::atexit([] {
      PetscBool finalized = PETSC_FALSE;
      PetscFinalized(&finalized);
      if (!finalized) PetscFinalize();
    });
  }

  std::unique_ptr<LinearSolver> make_solver(const SolverSpec& spec, const UnknownLayout& layout,
                                            std::string& failure) override {
    try {
      return std::make_unique<KrylovSolver>(spec, layout);
    } catch (const PetscFailure& e) {
      failure = e.what();
      return nullptr;
    }
  }

  std::string version() const override {
    std::string v = std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR) + "." +
                    std::to_string(PETSC_VERSION_SUBMINOR);
#if defined(PETSC_HAVE_HYPRE)
    v += " with hypre";
#endif
#if defined(PETSC_HAVE_MUMPS)
    v += " with MUMPS";
#endif
    return v;
  }

  const Communicator& world() const override { return world_; }

 private:
  MpiWorld world_;
};

}  // namespace
}  // namespace moreau::petsc_plugin

extern "C" __attribute__((visibility("default"))) moreau::petsc_plugin::Backend* moreau_petsc_backend(
    int interface_version, std::string* failure) {
  using namespace moreau::petsc_plugin;
  if (interface_version != kInterfaceVersion) {
    if (failure)
      *failure = "the PETSc plugin was built for interface version " + std::to_string(kInterfaceVersion) +
                 ", the engine asks for " + std::to_string(interface_version) + ": rebuild both together";
    return nullptr;
  }
  try {
    static PetscBackend backend;  // initialized once, thread-safe
    return &backend;
  } catch (const PetscFailure& e) {
    if (failure) *failure = e.what();
    return nullptr;
  }
}
