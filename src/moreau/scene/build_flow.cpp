// The "fluid" of a "solver": "fem" scene: an incompressible Navier-Stokes flow on a quad4/hex8
// mesh with velocity boundaries, outflows, a pressure reference and flow probes
// (docs/fem-scenes.md, "`fluid` (FEM)").
#include <fmt/format.h>

#include <limits>
#include <map>
#include <memory>

#include "moreau/fem/petsc/petsc_presets.hpp"
#include "moreau/fem/distributed/mpi_ranks.hpp"
#include "moreau/scene/fem_scene.hpp"

namespace moreau {

namespace {

using Components = std::shared_ptr<std::vector<std::unique_ptr<Expression>>>;

Index nearest_node(const FemMesh& mesh, const Vec3& at) {
  Index best = 0;
  for (Index n = 1; n < mesh.node_count(); ++n)
    if ((mesh.nodes[n] - at).squaredNorm() < (mesh.nodes[best] - at).squaredNorm()) best = n;
  return best;
}

// "boundaries": velocity conditions (later entries override earlier ones on shared nodes) and
// outflows; returns the velocity expression of each prescribed velocity dof.
std::map<Index, std::pair<Components, int>> read_flow_boundaries(const JsonObject& fluid, const NavierStokesModel& m) {
  std::map<Index, std::pair<Components, int>> velocity;
  for (const JsonObject& b : fluid.object_list("boundaries")) {
    const std::string type = b.choice("type", b.has("velocity") ? "velocity" : "no_slip", {"velocity", "no_slip", "outflow"});
    const std::vector<Index> nodes = select_nodes(b.object("where"), m.mesh, nullptr);
    if (type == "outflow") {
      // Do nothing: sigma n = 0 is the natural condition of the weak form.
      if (b.has("velocity")) b.fail("velocity", "an outflow boundary has no velocity (its traction sigma n is zero)");
      b.finish();
      continue;
    }
    Components value;
    if (type == "no_slip") {
      if (b.has("velocity")) b.fail("velocity", "a no_slip boundary has zero velocity; use \"type\": \"velocity\" to give one");
      value = std::make_shared<std::vector<std::unique_ptr<Expression>>>();
      for (int k = 0; k < m.dim(); ++k) value->push_back(std::make_unique<Expression>(0.0));
    } else {
      value = std::make_shared<std::vector<std::unique_ptr<Expression>>>(read_components(b, "velocity", m.dim(), true));
    }
    b.finish();
    for (Index n : nodes)
      for (int k = 0; k < m.dim(); ++k)
        if ((*value)[k]) velocity[m.dof(n, k)] = {value, k};
  }
  return velocity;
}

// True if every exterior facet has all its nodes' velocities prescribed: no natural boundary is
// left, so the pressure is determined only up to a constant.
bool velocity_everywhere_on_boundary(const NavierStokesModel& m, const std::map<Index, std::pair<Components, int>>& velocity) {
  for (Index n : exterior_facets(m.mesh))
    for (int k = 0; k < m.dim(); ++k)
      if (!velocity.count(m.dof(n, k))) return false;
  return true;
}

// {"type": "point", "object": <immersed solid>, "vertex": n | "nearest": [...], "quantity": "position" |
// "displacement" | "velocity"}: a node of an immersed solid, as the point probes of FEM solids.
void read_solid_point_probe(const JsonObject& j, const FlowProblem& problem, FlowProbe& p) {
  const std::string object = j.string("object");
  const FemSolid* solid = nullptr;
  if (problem.immersed)
    for (const FemSolid& s : problem.immersed->model.solids)
      if (s.name == object) solid = &s;
  if (!solid) {
    if (object == problem.name)
      j.fail("object", "a point of the fluid is given by \"at\" (a position, m), without \"object\"");
    j.fail("object", fmt::format("no solid named '{}' is immersed in the fluid", object));
  }
  if (j.has("vertex") == j.has("nearest"))
    j.fail("nearest", "give either \"vertex\" (a node index of the solid) or \"nearest\" (a point, m)");
  if (j.has("vertex")) {
    p.solid_node = solid->node_begin + j.required_integer("vertex", 0, static_cast<int>(solid->mesh.node_count()) - 1);
  } else {
    p.solid_node = solid->node_begin + nearest_node(solid->mesh, read_point(j, "nearest", solid->mesh.dim));
  }
  const std::string quantity = j.choice("quantity", "position", {"position", "displacement", "velocity"});
  p.type = FlowProbeType::solid_point;
  p.quantity = quantity;
}

// Coefficients 2 F / (rho U^2 L) per unit depth in 2D, 2 F / (rho U^2 A) in 3D, from a probe's
// "reference": {"velocity": U, "length": L | "area": A}; 0 without one.
Real read_force_coefficient_scale(const JsonObject& j, const NavierStokesModel& m) {
  const auto reference = j.optional_object("reference");
  if (!reference) return 0;
  const Real speed = reference->number("velocity", Range::positive());
  const Real size = m.dim() == 2 ? reference->number("length", Range::positive()) : reference->number("area", Range::positive());
  reference->finish();
  return 2 / (m.density * speed * speed * size);
}

// {"type": "force", "object": <immersed solid or rigid body>}: the fluid's force on it over the
// last step, with coefficients if given a "reference".
void read_solid_force_probe(const JsonObject& j, const FlowProblem& problem, FlowProbe& p) {
  const std::string object = j.string("object");
  if (problem.immersed)
    for (size_t s = 0; s < problem.immersed->model.solids.size(); ++s)
      if (problem.immersed->model.solids[s].name == object) p.solid = static_cast<Index>(s);
  if (p.solid < 0) j.fail("object", fmt::format("no solid or rigid body named '{}' is immersed in the fluid", object));
  p.type = FlowProbeType::solid_force;
  p.coefficient_scale = read_force_coefficient_scale(j, problem.model);
}

// {"type": "center_of_mass" | "velocity" | "angular_velocity" | "torque", "object": <immersed
// rigid body>}: its frame's centre, that centre's velocity, its angular velocity (2D: about z),
// or the fluid's torque on it about its centre over the last step.
void read_rigid_body_probe(const JsonObject& j, const std::string& type, const FlowProblem& problem, FlowProbe& p) {
  const std::string object = j.string("object");
  if (problem.immersed)
    for (size_t b = 0; b < problem.immersed->rigid_bodies.size(); ++b)
      if (problem.immersed->model.solids[problem.immersed->rigid_bodies[b].solid].name == object)
        p.body = static_cast<Index>(b);
  if (p.body < 0) j.fail("object", fmt::format("no rigid body named '{}' is immersed in the fluid", object));
  p.type = FlowProbeType::rigid_body;
  p.quantity = type;
}

FlowProbe read_flow_probe(const JsonObject& j, const FlowProblem& problem, const MeshLocator& locator) {
  const NavierStokesModel& m = problem.model;
  FlowProbe p;
  p.name = j.string("name");
  const std::string type = j.choice("type", {"point", "line", "boundary_force", "pressure_difference", "kinetic_energy",
                                             "energy", "newton_iterations", "center_of_mass", "velocity",
                                             "angular_velocity", "force", "torque"});
  // A sampled point: located once in the fluid's mesh, where it stays. `record` keeps it if it is
  // inside the mesh; `inside` also requires that it is.
  auto record = [&](const Vec3& at) {
    const std::optional<MeshPoint> found = locator.locate(at);
    if (found) {
      p.sample_points.push_back(at);
      p.located.push_back(*found);
    }
    return found.has_value();
  };
  auto inside = [&](const std::string& key) {
    const Vec3 at = read_point(j, key, m.dim());
    if (!record(at)) j.fail(key, "the point is outside the fluid mesh");
  };
  if (type == "point" && j.has("object")) {
    read_solid_point_probe(j, problem, p);
  } else if (type == "force") {
    read_solid_force_probe(j, problem, p);
  } else if (type == "center_of_mass" || type == "velocity" || type == "angular_velocity" || type == "torque") {
    read_rigid_body_probe(j, type, problem, p);
  } else if (type == "energy") {
    p.type = FlowProbeType::energy;
  } else if (type == "point") {
    p.type = FlowProbeType::point;
    inside("at");
  } else if (type == "line") {
    p.type = FlowProbeType::line;
    const Vec3 from = read_point(j, "from", m.dim()), to = read_point(j, "to", m.dim());
    const int samples = j.integer("samples", 101, 2, 1000000);
    // Samples in a gap of the mesh (an obstacle cut out of it) are left out.
    for (int s = 0; s < samples; ++s) record(from + (to - from) * (static_cast<Real>(s) / (samples - 1)));
  } else if (type == "pressure_difference") {
    p.type = FlowProbeType::pressure_difference;
    inside("from");
    inside("to");
  } else if (type == "boundary_force") {
    p.type = FlowProbeType::boundary_force;
    p.nodes = select_nodes(j.object("where"), m.mesh, nullptr);
    p.coefficient_scale = read_force_coefficient_scale(j, m);
  } else if (type == "kinetic_energy") {
    p.type = FlowProbeType::kinetic_energy;
  } else {
    p.type = FlowProbeType::newton_iterations;
  }
  j.finish();
  return p;
}

void read_flow_settings(const JsonObject* settings, const JsonObject& fluid, FlowProblem& problem) {
  std::string integrator = "midpoint";
  if (settings) integrator = settings->choice("integrator", integrator, {"steady", "midpoint", "backward_euler", "bdf2"});
  if (fluid.boolean("steady", false)) {
    if (settings && settings->has("integrator") && integrator != "steady")
      fluid.fail("steady", fmt::format("\"steady\": true contradicts \"integrator\": \"{}\"", integrator));
    integrator = "steady";
  }
  problem.integrator = integrator == "steady"           ? FlowIntegrator::steady
                       : integrator == "backward_euler" ? FlowIntegrator::backward_euler
                       : integrator == "bdf2"           ? FlowIntegrator::bdf2
                                                        : FlowIntegrator::midpoint;
  if (problem.integrator == FlowIntegrator::bdf2) problem.max_step_halvings = 0;  // its formula needs equal steps
  if (!settings) return;
  if (auto newton = settings->optional_object("newton")) {
    FlowSolveSettings& s = problem.solve;
    s.tolerance = newton->number("tolerance", s.tolerance, Range::open(0, 1));
    s.max_iterations = newton->integer("max_iterations", s.max_iterations, 1, 1000);
    s.picard_fallback = newton->boolean("picard_fallback", s.picard_fallback);
    s.max_picard_iterations = newton->integer("max_picard_iterations", s.max_picard_iterations, 1, 100000);
    if (problem.integrator == FlowIntegrator::bdf2) {
      if (newton->has("max_step_halvings") && newton->integer("max_step_halvings", 0, 0, 10) != 0)
        newton->fail("max_step_halvings", "\"bdf2\" needs equal steps: a failed step cannot be retried in substeps; "
                                          "use 0, or \"integrator\": \"midpoint\" or \"backward_euler\"");
    } else {
      problem.max_step_halvings = newton->integer("max_step_halvings", problem.max_step_halvings, 0, 10);
    }
    newton->finish();
  }
  if (auto linear = settings->optional_object("linear_solver")) {
    FlowLinearSettings& s = problem.linear;
    const std::string type = linear->choice("type", "direct", {"direct", "gmres", "petsc"});
    s.method = type == "gmres" ? FlowLinearMethod::gmres : type == "petsc" ? FlowLinearMethod::petsc : FlowLinearMethod::direct;
    const auto only_for = [&](std::initializer_list<const char*> keys, bool allowed, const char* whose) {
      for (const char* key : keys)
        if (!allowed && linear->has(key))
          linear->fail(key, fmt::format("\"{}\" is a setting of {}; \"type\": \"{}\" has none", key, whose, type));
    };
    only_for({"tolerance", "max_iterations", "restart"}, s.method != FlowLinearMethod::direct,
             "the iterative solvers (\"gmres\", \"petsc\")");
    only_for({"drop_tolerance", "fill_factor", "refresh_ratio"}, s.method == FlowLinearMethod::gmres,
             "\"type\": \"gmres\"");
    only_for({"preconditioner", "petsc_options"}, s.method == FlowLinearMethod::petsc, "\"type\": \"petsc\"");
    if (s.method != FlowLinearMethod::direct) {
      s.tolerance = linear->number("tolerance", s.tolerance, Range::open(0, 1));
      s.max_iterations = linear->integer("max_iterations", s.max_iterations, 1, 1000000);
      s.restart = linear->integer("restart", s.restart, 1, 10000);
    }
    if (s.method == FlowLinearMethod::gmres) {
      s.drop_tolerance = linear->number("drop_tolerance", s.drop_tolerance, Range::open(0, 1));
      s.fill_factor = linear->integer("fill_factor", s.fill_factor, 1, 1000);
      s.refresh_ratio = linear->number("refresh_ratio", s.refresh_ratio, Range::closed(1, 1e6));
    }
    if (s.method == FlowLinearMethod::petsc) {
      s.preconditioner = linear->choice("preconditioner", s.preconditioner, flow_petsc_preconditioners());
      if (linear->has("petsc_options")) s.petsc_options = linear->string("petsc_options");
      s.options_warning = require_petsc(*linear, {flow_petsc_options(s.preconditioner, s.restart) + " " + s.petsc_options},
                                        PetscSystemKind::flow);
    }
    linear->finish();
  }
}

}  // namespace

void build_flow_scene(const JsonObject& top, const JsonObject& fluid, const std::vector<JsonObject>& solids,
                      const std::vector<JsonObject>& rigid_bodies, const JsonObject* settings, FemProblem& fem,
                      const Vec3& gravity, int threads) {
  FlowProblem& problem = fem.flow.emplace();
  problem.name = fluid.string("name");
  read_flow_settings(settings, fluid, problem);
  fem.threads = threads;
  NavierStokesModel& m = problem.model;
  m.mesh = read_fem_mesh(fluid.object("mesh"), top.file() + ": " + fluid.path_of("mesh"), MeshUse::flow);
  if (m.mesh.element != ElementType::quad4 && m.mesh.element != ElementType::hex8)
    fluid.fail("mesh", fmt::format("the fluid needs quadrilateral (2D) or hexahedral (3D) cells, not {}; with Gmsh, "
                                   "recombine the mesh (\"Recombine Surface{{...}};\" in the .geo file)",
                                   element_name(m.mesh.element)));
  fem.model.dim = m.dim();
  m.density = fluid.number("density", Range::positive());
  m.viscosity = fluid.number("viscosity", Range::positive());
  m.body_force = gravity;
  if (m.dim() == 2) m.body_force.z() = 0;
  if (fluid.has("body_force")) m.body_force += read_point(fluid, "body_force", m.dim());

  const auto velocity = read_flow_boundaries(fluid, m);
  for (const auto& [dof, expression] : velocity) {
    const Vec3 X = m.mesh.nodes[dof / m.fields()];
    const Components value = expression.first;
    const int k = expression.second;
    m.prescribed.push_back({dof, [value, k, X](Real t) { return (*(*value)[k])(t, X); }});
  }
  const bool closed = velocity_everywhere_on_boundary(m, velocity);
  if (auto reference = fluid.optional_object("pressure_reference")) {
    if (!closed)
      fluid.fail("pressure_reference",
                 "the fluid has a boundary without a prescribed velocity (an outflow, a do-nothing boundary), which "
                 "already fixes the pressure; remove \"pressure_reference\"");
    if (reference->has("point") == reference->has("mean"))
      reference->fail("point", "give either \"point\": [...] with \"value\", or \"mean\": <value>");
    if (reference->has("point")) {
      const Index node = nearest_node(m.mesh, read_point(*reference, "point", m.dim()));
      const Real value = reference->number("value", 0.0);
      m.prescribed.push_back({m.dof(node, m.dim()), [value](Real) { return value; }});
    } else {
      problem.mean_pressure = reference->number("mean");
      m.prescribed.push_back({m.dof(0, m.dim()), [](Real) { return 0.0; }});
    }
    reference->finish();
  } else if (closed) {
    fluid.fail("boundaries",
               "every boundary has a prescribed velocity, so the pressure is determined only up to a constant; add "
               "\"pressure_reference\": {\"point\": [...], \"value\": 0} or {\"mean\": 0}");
  }

  if (fluid.has("continuation")) {
    if (problem.integrator != FlowIntegrator::steady)
      fluid.fail("continuation", "continuation is for steady solves (\"steady\": true or \"integrator\": \"steady\")");
    const JsonObject continuation = fluid.object("continuation");
    const auto& raw = continuation.raw("viscosity");
    if (!raw.is_array() || raw.empty()) continuation.fail("viscosity", "expected a list of viscosities (Pa s), largest first");
    for (const auto& v : raw) {
      if (!v.is_number() || !(v.get<Real>() > 0)) continuation.fail("viscosity", fmt::format("{} is not a positive viscosity", v.dump()));
      problem.continuation.push_back(v.get<Real>());
    }
    problem.continuation_tolerance = continuation.number("tolerance", problem.continuation_tolerance, Range::open(0, 1));
    continuation.finish();
  }

  require_petsc_when_distributed(top, settings, problem.linear.method == FlowLinearMethod::petsc);
  if (mpi_ranks() > 1 && (!solids.empty() || !rigid_bodies.empty()))
    top.fail("objects", fmt::format("a flow with immersed solids runs on one process, not on {} MPI ranks", mpi_ranks()));
  setup_navier_stokes(m, mpi_world());
  problem.initial = VectorX::Zero(m.dof_count());
  if (fluid.has("initial_velocity")) {
    const auto initial = read_components(fluid, "initial_velocity", m.dim(), false);
    for (Index n = 0; n < m.mesh.node_count(); ++n)
      for (int k = 0; k < m.dim(); ++k) problem.initial[m.dof(n, k)] = (*initial[k])(0, m.mesh.nodes[n]);
  }
  for (const PrescribedDof& p : m.prescribed) problem.initial[p.dof] = p.value(0);
  fluid.finish();
  if (!solids.empty() || !rigid_bodies.empty()) read_immersed_solids(top, solids, rigid_bodies, fem.dt, problem);
  const MeshLocator locator(m.mesh);
  for (const JsonObject& probe : top.object_list("probes")) {
    problem.probes.push_back(read_flow_probe(probe, problem, locator));
    for (size_t i = 0; i + 1 < problem.probes.size(); ++i)
      if (problem.probes[i].name == problem.probes.back().name)
        probe.fail("name", fmt::format("another probe is already named '{}'", problem.probes.back().name));
  }
}

}  // namespace moreau
