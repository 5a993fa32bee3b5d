#include "moreau/fem/petsc/petsc_plugin_loader.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace moreau {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPluginFile = "libmoreau_petsc.so";

std::vector<fs::path> plugin_candidates() {
  std::vector<fs::path> candidates;
  if (const char* named = std::getenv("MOREAU_PETSC_PLUGIN"); named && *named) {
    candidates.emplace_back(named);
    return candidates;
  }
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    candidates.push_back(program.parent_path() / kPluginFile);
    candidates.push_back(program.parent_path() / ".." / "lib" / "moreau" / kPluginFile);
  }
#ifdef MOREAU_PLUGIN_BUILD_DIR
  candidates.push_back(fs::path(MOREAU_PLUGIN_BUILD_DIR) / kPluginFile);
#endif
  return candidates;
}

petsc_plugin::Backend* load_backend() {
  std::string tried;
  for (const fs::path& path : plugin_candidates()) {
    if (!fs::exists(path)) {
      tried += fmt::format("\n  {}: not there", path.string());
      continue;
    }
    // RTLD_GLOBAL: Open MPI loads its own components with dlopen, and they look for the MPI
    // library's symbols in the global scope.
    void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (!library) {
      tried += fmt::format("\n  {}: {}", path.string(), dlerror());
      continue;
    }
    using Entry = petsc_plugin::Backend* (*)(int, std::string*);
    auto entry = reinterpret_cast<Entry>(dlsym(library, "moreau_petsc_backend"));
    if (!entry) {
      tried += fmt::format("\n  {}: no moreau_petsc_backend in it", path.string());
      continue;
    }
    std::string failure;
    if (petsc_plugin::Backend* backend = entry(petsc_plugin::kInterfaceVersion, &failure)) return backend;
    throw std::runtime_error(fmt::format("the PETSc plugin {} did not start: {}", path.string(), failure));
  }
  throw std::runtime_error(fmt::format(
      "the PETSc solvers need the plugin {}, built with the engine when PETSc is installed "
      "(scripts/install-deps.sh installs Debian's petsc-dev); looked in:{}",
      kPluginFile, tried));
}

}  // namespace

petsc_plugin::Backend& petsc_backend() {
  static std::mutex guard;
  static petsc_plugin::Backend* backend = nullptr;
  std::lock_guard lock(guard);
  if (!backend) backend = load_backend();
  return *backend;
}

}  // namespace moreau
