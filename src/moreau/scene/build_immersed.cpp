// The "solid" and "rigid_body" objects of a "solver": "fem" scene that has a fluid: deformable
// solids and rigid bodies immersed in it (fem/immersed; docs/fem-scenes.md, "Solids in a fluid").
// Solids move with the fluid's velocity, free rigid bodies with the fluid that their frame holds,
// so neither takes an initial velocity or loads of its own; gravity acts through the difference of
// their density and the fluid's. A driven rigid body follows its prescribed "motion".
#include <fmt/format.h>

#include <memory>
#include <optional>

#include "moreau/fem/core/mesh_locator.hpp"
#include "moreau/fem/immersed/immersed_rigid_body.hpp"
#include "moreau/scene/fem_scene.hpp"

namespace moreau {

namespace {

// Every node the fluid carries must start inside it (`held`: per node, how many of its components
// a "dirichlet" prescribes; a node held in every component need not).
void require_inside_fluid(const JsonObject& j, const FemMesh& mesh, const MeshLocator& locator, const std::vector<int>& held,
                          int dim, const char* what) {
  for (Index n = 0; n < mesh.node_count(); ++n)
    if (held[n] < dim && !locator.locate(mesh.nodes[n])) {
      const Vec3& p = mesh.nodes[n];
      j.fail("mesh", fmt::format("node {} at ({:.6g}, {:.6g}, {:.6g}) m lies outside the fluid's mesh; {}", n, p.x(), p.y(),
                                 p.z(), what));
    }
}

// "motion": {"velocity": [..], "angular_velocity": [x, y, z]}, each entry a number or an expression
// of t; either may be left out (zero). 2D: the angular velocity is about z.
PrescribedRigidMotion read_rigid_motion(const JsonObject& j, int dim) {
  using Components = std::shared_ptr<std::vector<std::unique_ptr<Expression>>>;
  auto components = [&](const char* key, int count) {
    Components c = std::make_shared<std::vector<std::unique_ptr<Expression>>>();
    if (j.has(key)) *c = read_components(j, key, count, false);
    for (const auto& e : *c)
      if (e->uses_position())
        j.fail(key, fmt::format("\"{}\": a body's motion is a function of t only (x, y, z are for boundary values)", e->text()));
    return c;
  };
  const Components velocity = components("velocity", dim), turning = components("angular_velocity", 3);
  if (dim == 2 && j.has("angular_velocity"))
    for (int k = 0; k < 2; ++k) {
      const auto& entry = j.raw("angular_velocity")[k];
      if (!entry.is_number() || entry.get<Real>() != 0)
        j.fail("angular_velocity", "a 2D body turns about z only: give [0, 0, w] (w a number or an expression of t)");
    }
  j.finish();
  auto at = [](const Components& c) {
    return [c](Real t) {
      Vec3 v = Vec3::Zero();
      for (size_t k = 0; k < c->size(); ++k) v[k] = (*(*c)[k])(t);
      return v;
    };
  };
  return {at(velocity), at(turning)};
}

// A rigid body beside a fluid: its mesh, density (a free body) or motion (a driven one) and the
// coupling's stiffness.
void read_immersed_rigid_body(const JsonObject& top, const JsonObject& bj, Real dt, const MeshLocator& locator,
                              FlowProblem& problem) {
  const NavierStokesModel& fluid = problem.model;
  ImmersedSolids& immersed = *problem.immersed;
  for (const char* key : {"velocity", "angular_velocity"})
    if (bj.has(key))
      bj.fail(key, "a free rigid body in a fluid starts at rest with the fluid around it: give the fluid an "
                   "\"initial_velocity\" instead, or drive the body with \"motion\": {\"velocity\": [..], "
                   "\"angular_velocity\": [..]}");
  FemSolid solid;
  solid.name = bj.string("name");
  solid.mesh = read_fem_mesh(bj.object("mesh"), top.file() + ": " + bj.path_of("mesh"), MeshUse::solid);
  if (solid.mesh.dim != fluid.dim())
    bj.fail("mesh", fmt::format("the fluid is {}D, so the rigid bodies in it are too (\"type\": \"{}\", or a {}D Gmsh mesh)",
                                fluid.dim(), fluid.dim() == 2 ? "rectangle" : "box", fluid.dim()));
  std::optional<PrescribedRigidMotion> motion;
  if (const auto motion_json = bj.optional_object("motion")) {
    if (bj.has("density"))
      bj.fail("density", "a driven body (with \"motion\") moves as prescribed whatever its mass: leave out \"density\"");
    motion = read_rigid_motion(*motion_json, fluid.dim());
    solid.material.density = fluid.density;  // its mesh's mass only gives its nodes' volumes
  } else {
    solid.material.density = bj.number("density", Range::positive());  // no stiffness: its stress is zero
  }
  if (problem.linear.method != FlowLinearMethod::direct)
    bj.fail("kind", "a fluid with rigid bodies needs the direct linear solver (\"linear_solver\": {\"type\": \"direct\"}): "
                    "the bodies' part of the Jacobian is applied through extra solves that an iterative solver, "
                    "solving each only to its tolerance, cannot make accurate enough");
  const Real stiffness = bj.number("coupling_stiffness", default_rigid_coupling_stiffness(fluid, dt), Range::positive());
  // A body lighter than the fluid has a negative excess mass; its frame's equations stay
  // well-posed while theta k outweighs (rho_f - rho_s)/dt (theta = 1/2 at worst), with a margin.
  const Real lightest = 20 * (fluid.density - solid.material.density) / dt;
  if (!motion && stiffness < lightest)
    bj.fail("coupling_stiffness", fmt::format("a body lighter than the fluid needs a coupling stiffness of at least "
                                              "20 (rho_f - rho_s) / dt = {:.4g} Pa s/m^2", lightest));
  add_fem_solid(immersed.model, std::move(solid));
  immersed.viscosity.push_back(fluid.viscosity);
  const Index index = static_cast<Index>(immersed.model.solids.size()) - 1;
  immersed.rigid_bodies.push_back(make_immersed_rigid_body(immersed.model, index, fluid.density, stiffness));
  immersed.rigid_bodies.back().motion = std::move(motion);
  require_inside_fluid(bj, immersed.model.solids.back().mesh, locator,
                       std::vector<int>(immersed.model.solids.back().mesh.node_count(), 0), fluid.dim(),
                       "a rigid body must lie inside the fluid");
  bj.finish();
}

}  // namespace

void read_immersed_solids(const JsonObject& top, const std::vector<JsonObject>& solids,
                          const std::vector<JsonObject>& rigid_bodies, Real dt, FlowProblem& problem) {
  const std::vector<JsonObject>& first = solids.empty() ? rigid_bodies : solids;
  const NavierStokesModel& fluid = problem.model;
  if (problem.integrator != FlowIntegrator::midpoint && problem.integrator != FlowIntegrator::backward_euler)
    first[0].fail("kind", "a fluid with immersed solids or rigid bodies is stepped in time with \"integrator\": \"midpoint\" or "
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
    std::vector<int> held(added.mesh.node_count(), 0);
    for (size_t i = before; i < immersed.model.prescribed.size(); ++i)
      ++held[immersed.model.prescribed[i].dof / fluid.dim() - added.node_begin];
    require_inside_fluid(sj, added.mesh, locator, held, fluid.dim(),
                         "an immersed solid must lie inside the fluid (only nodes clamped by \"dirichlet\" may not)");
    sj.finish();
  }
  for (const JsonObject& bj : rigid_bodies) read_immersed_rigid_body(top, bj, dt, locator, problem);
  finalize_fem_model(immersed.model);
}

}  // namespace moreau
