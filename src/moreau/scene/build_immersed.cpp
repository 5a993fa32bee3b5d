// The "solid" objects of a "solver": "fem" scene that has a fluid: deformable solids immersed in it
// (fem/immersed; docs/fem-scenes.md, "Solids in a fluid"). They move with the fluid's velocity,
// so they take no initial velocity or loads of their own; gravity acts through the difference of
// their density and the fluid's.
#include <fmt/format.h>

#include "moreau/fem/core/mesh_locator.hpp"
#include "moreau/scene/fem_scene.hpp"

namespace moreau {

void read_immersed_solids(const JsonObject& top, const std::vector<JsonObject>& solids, FlowProblem& problem) {
  const NavierStokesModel& fluid = problem.model;
  if (problem.integrator != FlowIntegrator::midpoint && problem.integrator != FlowIntegrator::backward_euler)
    solids[0].fail("kind", "a fluid with immersed solids is stepped in time with \"integrator\": \"midpoint\" or "
                           "\"backward_euler\" (a steady state is reached by stepping)");
  ImmersedSolids& immersed = problem.immersed.emplace();
  immersed.model.dim = fluid.dim();
  const MeshLocator locator(fluid.mesh);
  for (const JsonObject& sj : solids) {
    if (sj.has("velocity"))
      sj.fail("velocity", "an immersed solid moves with the fluid: give the fluid an \"initial_velocity\" instead");
    if (sj.has("loads"))
      sj.fail("loads", "an immersed solid takes no loads of its own: the fluid carries it, and gravity acts on it "
                       "through the difference of its density and the fluid's");
    FemSolid solid;
    solid.name = sj.string("name");
    solid.mesh = read_fem_mesh(sj.object("mesh"), top.file() + ": " + sj.path_of("mesh"), MeshUse::solid);
    if (solid.mesh.dim != fluid.dim())
      sj.fail("mesh", fmt::format("the fluid is {}D, so its immersed solids are too (\"type\": \"{}\")", fluid.dim(),
                                  fluid.dim() == 2 ? "rectangle" : "box"));
    solid.material = read_fem_material(sj.object("material"));
    solid.volume = read_volume_treatment(sj, solid);
    immersed.viscosity.push_back(sj.number("viscosity", fluid.viscosity, Range::non_negative()));
    add_fem_solid(immersed.model, std::move(solid));
    const FemSolid& added = immersed.model.solids.back();
    const size_t before = immersed.model.prescribed.size();
    read_dirichlet(sj, immersed.model, static_cast<Index>(immersed.model.solids.size()) - 1);
    // Every node the fluid carries must start inside it (a node held in every component need not).
    std::vector<int> held(added.mesh.node_count(), 0);
    for (size_t i = before; i < immersed.model.prescribed.size(); ++i)
      ++held[immersed.model.prescribed[i].dof / fluid.dim() - added.node_begin];
    for (Index n = 0; n < added.mesh.node_count(); ++n)
      if (held[n] < fluid.dim() && !locator.locate(added.mesh.nodes[n])) {
        const Vec3& p = added.mesh.nodes[n];
        sj.fail("mesh", fmt::format("node {} at ({:.6g}, {:.6g}, {:.6g}) m lies outside the fluid's mesh; an immersed "
                                    "solid must lie inside the fluid (only nodes clamped by \"dirichlet\" may not)",
                                    n, p.x(), p.y(), p.z()));
      }
    sj.finish();
  }
  finalize_fem_model(immersed.model);
}

}  // namespace moreau
