#pragma once
// The formulations a scene can name in `settings.solver`. Adding a solver: implement Solver
// (solver.hpp) in solvers/<name>/ and add one entry to the registry in solver_registry.cpp
// (docs/architecture.md, "Adding a solver").
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "moreau/solvers/solver.hpp"

namespace moreau {

/// The registered formulations' names, in registry order.
std::vector<std::string> registered_solver_names();

/// Why the registered formulation `name` cannot step `model` (what the scene holds that it does
/// not simulate), or an empty string when it can.
std::string solver_refusal(std::string_view name, const Model& model);

/// A new solver for `model`, or nullptr when `name` is not registered.
std::unique_ptr<Solver> make_solver(std::string_view name, const Model& model);

}  // namespace moreau
