#include "moreau/solvers/solver_registry.hpp"

#include <functional>

#include "moreau/solvers/xpbd/xpbd_solver.hpp"

namespace moreau {

namespace {

struct SolverEntry {
  std::string_view name;
  std::function<std::unique_ptr<Solver>(const Model&)> make;
};

const std::vector<SolverEntry>& registry() {
  static const std::vector<SolverEntry> entries{
      {"xpbd", [](const Model&) { return std::make_unique<XpbdSolver>(); }},
  };
  return entries;
}

}  // namespace

std::vector<std::string> registered_solver_names() {
  std::vector<std::string> names;
  for (const SolverEntry& e : registry()) names.emplace_back(e.name);
  return names;
}

std::unique_ptr<Solver> make_solver(std::string_view name, const Model& model) {
  for (const SolverEntry& e : registry())
    if (e.name == name) return e.make(model);
  return nullptr;
}

}  // namespace moreau
