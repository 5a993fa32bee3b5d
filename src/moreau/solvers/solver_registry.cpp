#include "moreau/solvers/solver_registry.hpp"

#include <fmt/format.h>

#include <functional>

#include "moreau/solvers/nmd/nmd_solver.hpp"
#include "moreau/solvers/xpbd/xpbd_solver.hpp"
#include "moreau/solvers/xpbi/xpbi_solver.hpp"

namespace moreau {

namespace {

struct SolverEntry {
  std::string_view name;
  std::function<std::unique_ptr<Solver>(const Model&)> make;
  std::function<std::string(const Model&)> refusal;  // empty: every constraint scene
};

// The continua (kind "continuum") are simulated by XPBI alone.
std::string continuum_refusal(std::string_view solver, const Model& model) {
  for (const ObjectInfo& o : model.objects)
    if (o.kind == ObjectKind::continuum)
      return fmt::format("the '{}' formulation does not simulate continua ('{}' is a \"continuum\"); run with "
                         "\"solver\": \"xpbi\"",
                         solver, o.name);
  return {};
}

std::string no_suction_cups(std::string_view solver, const Model& model) {
  if (!model.suction_cups.empty())
    return fmt::format("the '{}' formulation does not simulate suction cups (a soft body's \"suction\"); run with "
                       "\"solver\": \"nmd\"",
                       solver);
  return {};
}

std::string xpbd_refusal(const Model& model) {
  if (std::string why = no_suction_cups("xpbd", model); !why.empty()) return why;
  return continuum_refusal("xpbd", model);
}

std::string xpbi_refusal(const Model& model) { return no_suction_cups("xpbi", model); }

// A shape-matching cluster of n particles has n^2 Jacobian blocks under nmd (shape_match_rows.hpp).
constexpr Index kMaxNmdClusterSize = 512;

// Melting and freezing fix solid fluid particles in place (fluid_heat.hpp), which the XPBD step
// does; the velocity-level fluid rows do not.
std::string melting_refusal(std::string_view solver, const Model& model) {
  for (const ObjectInfo& o : model.objects)
    if (o.kind == ObjectKind::fluid && model.fluid.phases[o.fluid_phase].melting_point)
      return fmt::format("the '{}' formulation does not simulate melting and freezing ('{}' has a \"melting_point\"); "
                         "run with \"solver\": \"xpbd\" (heat conduction alone runs under every formulation)",
                         solver, o.name);
  return {};
}

std::string nmd_refusal(const Model& model) {
  if (std::string why = continuum_refusal("nmd", model); !why.empty()) return why;
  if (std::string why = melting_refusal("nmd", model); !why.empty()) return why;
  const ShapeMatchClusters& clusters = model.shape_matching;
  for (Index k = 0; k < clusters.size(); ++k) {
    const Index size = clusters.offsets[k + 1] - clusters.offsets[k];
    if (size > kMaxNmdClusterSize)
      return fmt::format("under 'nmd' a shape-matching cluster may hold at most {} particles (its rows grow with the "
                         "square of its size); '{}' has one of {}: split it with \"clusters\": {{\"radius\": ...}}",
                         kMaxNmdClusterSize, model.objects[clusters.object[k]].name, size);
  }
  return {};
}

const std::vector<SolverEntry>& registry() {
  static const std::vector<SolverEntry> entries{
      {"xpbd", [](const Model&) { return std::make_unique<XpbdSolver>(); }, xpbd_refusal},
      {"nmd", [](const Model&) { return std::make_unique<NmdSolver>(); }, nmd_refusal},
      {"xpbi", [](const Model&) { return std::make_unique<XpbiSolver>(); }, xpbi_refusal},
  };
  return entries;
}

}  // namespace

std::vector<std::string> registered_solver_names() {
  std::vector<std::string> names;
  for (const SolverEntry& e : registry()) names.emplace_back(e.name);
  return names;
}

std::string solver_refusal(std::string_view name, const Model& model) {
  for (const SolverEntry& e : registry())
    if (e.name == name) return e.refusal ? e.refusal(model) : std::string();
  return {};
}

std::unique_ptr<Solver> make_solver(std::string_view name, const Model& model) {
  for (const SolverEntry& e : registry())
    if (e.name == name) return e.make(model);
  return nullptr;
}

}  // namespace moreau
