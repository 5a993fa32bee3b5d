// Scenes of the FEM engine ("solver": "fem"): "objects" of kind "solid" (a mesh, a hyperelastic
// material, loads and Dirichlet conditions), "rigid_body" (director bodies) and "fluid"
// (build_flow.cpp), "joints" and FEM probes (docs/fem-scenes.md).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <memory>

#include "moreau/fem/distributed/mpi_ranks.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"
#include "moreau/fem/solids/solid_partition.hpp"
#include "moreau/math/expression.hpp"
#include "moreau/fem/petsc/petsc_presets.hpp"
#include "moreau/scene/fem_scene.hpp"

namespace moreau {

HyperelasticMaterial read_fem_material(const JsonObject& m) {
  HyperelasticMaterial material;
  material.model = m.choice("model", "neo_hookean", {"neo_hookean", "st_venant_kirchhoff"}) == "neo_hookean"
                       ? HyperelasticModel::neo_hookean
                       : HyperelasticModel::st_venant_kirchhoff;
  const bool youngs = m.has("youngs_modulus") || m.has("poisson_ratio");
  const bool lame = m.has("lame_lambda") || m.has("lame_mu");
  if (youngs == lame)
    m.fail("youngs_modulus", "give either \"youngs_modulus\" and \"poisson_ratio\" or \"lame_lambda\" and \"lame_mu\"");
  if (youngs) {
    material.lame = lame_from_youngs(m.number("youngs_modulus", Range::positive()),
                                     m.number("poisson_ratio", Range{-1, 0.5, true, true}));
  } else {
    material.lame = {m.number("lame_lambda", Range::non_negative()), m.number("lame_mu", Range::positive())};
  }
  material.density = m.number("density", Range::positive());
  m.finish();
  return material;
}

VolumeTreatment read_volume_treatment(const JsonObject& sj, const FemSolid& solid) {
  if (sj.choice("formulation", "displacement", {"displacement", "mean_dilatation"}) == "displacement")
    return VolumeTreatment::pointwise;
  if (solid.material.model != HyperelasticModel::neo_hookean)
    sj.fail("formulation", "\"mean_dilatation\" evaluates the Neo-Hookean volumetric energy lambda/2 (ln J)^2 at each "
                           "cell's mean J; give the solid's \"material\" \"model\": \"neo_hookean\"");
  if (solid.mesh.element != ElementType::quad4 && solid.mesh.element != ElementType::hex8)
    sj.fail("formulation", fmt::format("\"mean_dilatation\" needs quad4 or hex8 cells (a {} cell has one quadrature "
                                       "point, whose J is already the mean)", element_name(solid.mesh.element)));
  return VolumeTreatment::mean_dilatation;
}

namespace {

void read_loads(const JsonObject& solid_json, FemModel& model, Index solid) {
  for (const JsonObject& load : solid_json.object_list("loads")) {
    const FemSolid& s = model.solids[solid];
    const std::string type = load.choice("type", {"nodal_force", "traction"});
    std::string boundary;
    const std::vector<Index> nodes = select_nodes(load.object("where"), s.mesh, &boundary);
    NodalLoad l;
    l.name = load.path();
    if (type == "traction") {
      if (boundary.empty()) load.fail("where", "a traction acts on a named boundary: {\"boundary\": \"<name>\"}");
      facet_node_integrals(s, boundary, l.nodes, l.weights);
    } else {
      l.nodes = nodes;
      l.weights.assign(nodes.size(), 1.0);
    }
    for (Index& n : l.nodes) n += s.node_begin;
    std::shared_ptr<std::vector<std::unique_ptr<Expression>>> value(
        new std::vector<std::unique_ptr<Expression>>(read_components(load, "value", model.dim, false)));
    for (const auto& e : *value)
      if (e->uses_position())
        load.fail("value", fmt::format("\"{}\": load values are functions of t only (x, y, z are for Dirichlet values)", e->text()));
    l.value = [value](Real t) {
      Vec3 v = Vec3::Zero();
      for (size_t k = 0; k < value->size(); ++k) v[k] = (*(*value)[k])(t);
      return v;
    };
    load.finish();
    model.loads.push_back(std::move(l));
  }
}

}  // namespace

void read_dirichlet(const JsonObject& solid_json, FemModel& model, Index solid) {
  for (const JsonObject& bc : solid_json.object_list("dirichlet")) {
    const FemSolid& s = model.solids[solid];
    const std::vector<Index> nodes = select_nodes(bc.object("where"), s.mesh, nullptr);
    std::shared_ptr<std::vector<std::unique_ptr<Expression>>> value(
        new std::vector<std::unique_ptr<Expression>>(read_components(bc, "value", model.dim, true)));
    for (Index n : nodes)
      for (int k = 0; k < model.dim; ++k) {
        if (!(*value)[k]) continue;
        const Vec3 X = s.mesh.nodes[n];
        model.prescribed.push_back({model.dof(s.node_begin + n, k), [value, k, X](Real t) { return (*(*value)[k])(t, X); }});
      }
    bc.finish();
  }
}

namespace {

// One end of a joint: "world", a rigid body or a solid, by name.
struct EndRef {
  FemJointEndKind kind = FemJointEndKind::world;
  Index index = -1;  // body, or solid
};

EndRef read_end(const JsonObject& j, const std::string& name, const FemProblem& problem) {
  if (name == "world") return {};
  for (size_t b = 0; b < problem.rigid_bodies.size(); ++b)
    if (problem.rigid_bodies[b].name == name) return {FemJointEndKind::body, static_cast<Index>(b)};
  for (size_t s = 0; s < problem.model.solids.size(); ++s)
    if (problem.model.solids[s].name == name) return {FemJointEndKind::node, static_cast<Index>(s)};
  j.fail("bodies", fmt::format("'{}' is not \"world\", a rigid body or a solid of this scene", name));
}

// The end's point at a world position (bodies: coordinates along the reference directors).
FemJointEnd point_end(const EndRef& e, const FemProblem& problem, const Vec3& at, Index node = -1) {
  switch (e.kind) {
    case FemJointEndKind::world: return {FemJointEndKind::world, -1, at};
    case FemJointEndKind::body: {
      const DirectorBody& b = problem.rigid_bodies[e.index].body;
      return {FemJointEndKind::body, e.index, b.axes.transpose() * (at - b.centre)};
    }
    case FemJointEndKind::node: return {FemJointEndKind::node, node, Vec3::Zero()};
  }
  return {};
}

// A direction fixed in an end: coordinates along a body's reference directors, or a world vector.
Vec3 end_direction(const EndRef& e, const FemProblem& problem, const Vec3& direction) {
  if (e.kind == FemJointEndKind::body) return problem.rigid_bodies[e.index].body.axes.transpose() * direction;
  return direction;
}

FemJoint read_fem_joint(const JsonObject& j, const FemProblem& problem) {
  FemJoint joint;
  joint.name = j.string("name");
  const std::string type = j.choice("type", {"spherical", "hinge"});
  const auto& bodies = j.raw("bodies");
  if (!bodies.is_array() || bodies.size() != 2 || !bodies[0].is_string() || !bodies[1].is_string())
    j.fail("bodies", "expected two names: [\"a\", \"b\"] (\"world\", a rigid body or a solid)");
  EndRef ends[2] = {read_end(j, bodies[0].get<std::string>(), problem), read_end(j, bodies[1].get<std::string>(), problem)};
  if (ends[0].kind == FemJointEndKind::world && ends[1].kind == FemJointEndKind::world)
    j.fail("bodies", "a joint needs an end that is not the world");
  if (ends[0].kind == ends[1].kind && ends[0].index == ends[1].index) j.fail("bodies", "a joint cannot join an end to itself");
  const Vec3 anchor = j.vec3("anchor");
  // A solid end holds its node nearest to the anchor (spherical) or every node on the hinge axis
  // (hinge).
  auto nearest_node = [&](Index solid) {
    const FemSolid& s = problem.model.solids[solid];
    Index best = 0;
    for (Index n = 1; n < s.mesh.node_count(); ++n)
      if ((s.mesh.nodes[n] - anchor).norm() < (s.mesh.nodes[best] - anchor).norm()) best = n;
    return s.node_begin + best;
  };
  if (type == "spherical") {
    Index node[2] = {-1, -1};
    for (int k = 0; k < 2; ++k)
      if (ends[k].kind == FemJointEndKind::node) node[k] = nearest_node(ends[k].index);
    const Vec3 at = node[0] >= 0 ? problem.model.reference_position(node[0])
                                 : node[1] >= 0 ? problem.model.reference_position(node[1]) : anchor;
    joint.rows.push_back({FemJointRows::Kind::coincide, point_end(ends[0], problem, at, node[0]),
                          point_end(ends[1], problem, at, node[1])});
    j.finish();
    return joint;
  }
  const Vec3 axis_in = j.vec3("axis");
  if (axis_in.norm() <= 0) j.fail("axis", "the hinge axis must not be zero");
  const Vec3 axis = axis_in.normalized();
  if (ends[0].kind == FemJointEndKind::node && ends[1].kind == FemJointEndKind::node)
    j.fail("bodies", "a hinge joins a rigid body (or the world) to another body, the world or a solid");
  if (ends[0].kind == FemJointEndKind::node) std::swap(ends[0], ends[1]);
  if (ends[1].kind == FemJointEndKind::node) {
    // Every node of the solid on the axis line through the anchor is held to end a's point there.
    const FemSolid& s = problem.model.solids[ends[1].index];
    Real size = 0;
    for (const Vec3& x : s.mesh.nodes) size = std::max(size, (x - s.mesh.nodes[0]).norm());
    for (Index n = 0; n < s.mesh.node_count(); ++n) {
      const Vec3 r = s.mesh.nodes[n] - anchor;
      if ((r - r.dot(axis) * axis).norm() > 1e-9 * size) continue;
      joint.rows.push_back({FemJointRows::Kind::coincide, point_end(ends[0], problem, s.mesh.nodes[n]),
                            point_end(ends[1], problem, s.mesh.nodes[n], s.node_begin + n)});
    }
    if (joint.rows.size() < 2)
      j.fail("anchor", fmt::format("solid '{}' has {} node(s) on the hinge axis through the anchor; a hinge to a "
                                   "solid needs at least two (place the axis along a mesh edge)",
                                   s.name, joint.rows.size()));
    j.finish();
    return joint;
  }
  // Between bodies or a body and the world: the anchor, and the axis of end a normal to two
  // directions of end b that are normal to the axis.
  joint.rows.push_back({FemJointRows::Kind::coincide, point_end(ends[0], problem, anchor), point_end(ends[1], problem, anchor)});
  const Vec3 e1 = (std::abs(axis.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY()).cross(axis).normalized(), e2 = axis.cross(e1);
  for (const Vec3& e : {e1, e2}) {
    FemJointRows row{FemJointRows::Kind::perpendicular, point_end(ends[0], problem, anchor), point_end(ends[1], problem, anchor)};
    row.direction_a = end_direction(ends[0], problem, axis);
    row.direction_b = end_direction(ends[1], problem, e);
    joint.rows.push_back(row);
  }
  j.finish();
  return joint;
}

FemProbe read_fem_probe(const JsonObject& j, const FemProblem& problem) {
  FemProbe p;
  p.name = j.string("name");
  // The probe types and keys of constraint-engine scenes, where the FEM engine has the quantity.
  const std::string type = j.choice("type", {"point", "energy", "momentum", "center_of_mass", "velocity",
                                             "angular_velocity", "newton_iterations", "constraint_error"});
  const bool of_body = type == "center_of_mass" || type == "velocity" || type == "angular_velocity";
  j.expect_keys(type == "point"               ? std::vector<std::string>{"name", "type", "object", "vertex", "nearest", "quantity"}
                : type == "angular_velocity" ? std::vector<std::string>{"name", "type", "object", "frame"}
                : of_body                    ? std::vector<std::string>{"name", "type", "object"}
                : type == "energy" || type == "momentum" ? std::vector<std::string>{"name", "type", "object", "quantity"}
                                                         : std::vector<std::string>{"name", "type"});
  // Energy and momentum are of the whole model; "*" says so as in constraint-engine scenes.
  if ((type == "energy" || type == "momentum") && j.has("object") && j.string("object") != "*")
    j.fail("object", "energy and momentum are of the whole model in a FEM scene: leave \"object\" out or give \"*\"");
  const FemModel& model = problem.model;
  if (type == "point") {
    const std::string object = j.string("object");
    const FemSolid* solid = nullptr;
    for (const FemSolid& s : model.solids)
      if (s.name == object) solid = &s;
    if (!solid) j.fail("object", fmt::format("no solid named '{}'", object));
    if (j.has("vertex") == j.has("nearest"))
      j.fail("nearest", "give either \"vertex\" (a node index of the solid) or \"nearest\" (a point, m)");
    if (j.has("vertex")) {
      p.node = solid->node_begin + j.required_integer("vertex", 0, static_cast<int>(solid->mesh.node_count()) - 1);
    } else {
      const Vec3 at = read_point(j, "nearest", model.dim);
      Real best = std::numeric_limits<Real>::infinity();
      for (Index n = 0; n < solid->mesh.node_count(); ++n)
        if ((solid->mesh.nodes[n] - at).norm() < best) {
          best = (solid->mesh.nodes[n] - at).norm();
          p.node = solid->node_begin + n;
        }
    }
    const std::string q = j.choice("quantity", "displacement", {"displacement", "position", "velocity"});
    p.type = q == "displacement" ? FemProbeType::displacement : q == "position" ? FemProbeType::position : FemProbeType::velocity;
  } else if (type == "energy") {
    p.type = FemProbeType::energy;
    p.quantity = j.choice("quantity", "total", {"kinetic", "elastic", "potential", "total"});
  } else if (type == "momentum") {
    p.type = FemProbeType::momentum;
    p.quantity = j.choice("quantity", "linear", {"linear", "angular"});
  } else if (of_body) {
    p.type = FemProbeType::body;
    const std::string object = j.string("object");
    for (size_t b = 0; b < problem.rigid_bodies.size(); ++b)
      if (problem.rigid_bodies[b].name == object) p.body = static_cast<Index>(b);
    if (p.body < 0) j.fail("object", fmt::format("no rigid body named '{}'", object));
    if (type == "center_of_mass") p.quantity = "position";
    else if (type == "velocity") p.quantity = "velocity";
    else
      p.quantity = j.choice("frame", "world", {"world", "body"}) == "world" ? "angular_velocity" : "body_angular_velocity";
  } else if (type == "constraint_error") {
    p.type = FemProbeType::constraint_error;
  } else {
    p.type = FemProbeType::newton_iterations;
  }
  j.finish();
  return p;
}

}  // namespace

void allow_fem_settings(const JsonObject& settings) {
  settings.allow("integrator");
  settings.allow("newton");
  settings.allow("linear_solver");
}

namespace {

// The solids' "integrator" and "newton" settings.
void read_solid_settings(const JsonObject& settings, FemProblem& problem) {
  const std::string integrator = settings.choice("integrator", "energy_momentum", {"static", "midpoint", "energy_momentum"});
  if (auto linear = settings.optional_object("linear_solver")) {
    SolidLinearSettings& s = problem.linear;
    s.petsc = linear->choice("type", "direct", {"direct", "petsc"}) == "petsc";
    for (const char* key : {"preconditioner", "tolerance", "max_iterations", "petsc_options"})
      if (!s.petsc && linear->has(key))
        linear->fail(key, fmt::format("\"{}\" is a setting of \"type\": \"petsc\"; the direct solvers (CHOLMOD, "
                                      "UMFPACK) have none",
                                      key));
    if (s.petsc) {
      s.preconditioner = linear->choice("preconditioner", s.preconditioner, solid_petsc_preconditioners());
      s.tolerance = linear->number("tolerance", s.tolerance, Range::open(0, 1));
      s.max_iterations = linear->integer("max_iterations", s.max_iterations, 1, 1000000);
      if (linear->has("petsc_options")) s.petsc_options = linear->string("petsc_options");
      // The energy-momentum scheme's tangents are not symmetric: its solver is the general one. The
      // symmetric solver's CG may fall back to that one too, so both are checked then.
      std::vector<std::string> solvers = {solid_solver_options(s, false)};
      if (integrator != "energy_momentum") solvers.insert(solvers.begin(), solid_solver_options(s, true));
      s.options_warning = require_petsc(*linear, solvers, PetscSystemKind::solid);
    }
    linear->finish();
  }
  problem.integrator = integrator == "static"     ? FemIntegrator::static_load_steps
                       : integrator == "midpoint" ? FemIntegrator::midpoint
                                                  : FemIntegrator::energy_momentum;
  if (auto newton = settings.optional_object("newton")) {
    problem.newton.tolerance = newton->number("tolerance", problem.newton.tolerance, Range::open(0, 1));
    problem.newton.max_iterations = newton->integer("max_iterations", problem.newton.max_iterations, 1, 1000);
    newton->finish();
  }
}

// The objects of a FEM scene by kind (indices into `all`, whose entries track the keys read).
struct FemObjects {
  std::vector<JsonObject> all;
  std::vector<size_t> solids, bodies, fluids;
};

FemObjects read_fem_objects(const JsonObject& top) {
  for (const char* key : {"solids", "rigid_bodies", "fluid"})
    if (top.has(key))
      top.fail(key, "a FEM scene lists its solids, rigid bodies and fluid under \"objects\", each with a \"name\" and a "
                    "\"kind\": \"solid\", \"rigid_body\" or \"fluid\"");
  FemObjects objects{top.object_list("objects"), {}, {}, {}};
  if (objects.all.empty())
    top.fail("objects", "a \"solver\": \"fem\" scene needs at least one object: a solid, a rigid body or a fluid");
  std::vector<std::string> names;
  for (size_t i = 0; i < objects.all.size(); ++i) {
    const JsonObject& o = objects.all[i];
    const std::string name = o.string("name");
    if (std::find(names.begin(), names.end(), name) != names.end())
      o.fail("name", fmt::format("another object is already named '{}'; names must be unique", name));
    names.push_back(name);
    const nlohmann::json& kind_raw = o.has("kind") ? o.raw("kind") : nlohmann::json();
    for (const char* xpbd_kind : {"cloth", "soft_body", "collider"})
      if (kind_raw == xpbd_kind)
        o.fail("kind", fmt::format("'{}' is a kind of the constraint engine (\"solver\": \"xpbd\"); a FEM scene holds "
                                   "\"solid\", \"rigid_body\" and \"fluid\" objects",
                                   xpbd_kind));
    const std::string kind = o.choice("kind", {"solid", "rigid_body", "fluid"});
    (kind == "solid" ? objects.solids : kind == "rigid_body" ? objects.bodies : objects.fluids).push_back(i);
  }
  if (objects.fluids.size() > 1)
    objects.all[objects.fluids[1]].fail("kind", "a FEM scene holds one fluid (one Navier-Stokes mesh)");
  if (!objects.fluids.empty() && top.has("joints"))
    top.fail("joints", "a fluid holds solids and rigid bodies (immersed in it), but not joints: the FEM engine does not "
                       "couple joints to a fluid; run them as a separate scene");
  return objects;
}

}  // namespace

void build_fem_scene(const JsonObject& top, FemProblem& problem, const Vec3& gravity, int threads) {
  const std::optional<JsonObject> settings = top.optional_object("settings");
  FemObjects objects = read_fem_objects(top);
  if (!objects.fluids.empty()) {
    std::vector<JsonObject> solids, bodies;
    for (size_t i : objects.solids) solids.push_back(objects.all[i]);
    for (size_t i : objects.bodies) bodies.push_back(objects.all[i]);
    build_flow_scene(top, objects.all[objects.fluids[0]], solids, bodies, settings ? &*settings : nullptr, problem, gravity,
                     threads);
    return;
  }
  if (settings) read_solid_settings(*settings, problem);
  require_petsc_when_distributed(top, settings ? &*settings : nullptr, problem.linear.petsc);
  FemModel& model = problem.model;
  problem.threads = threads;
  if (objects.solids.empty()) model.dim = 3;
  std::vector<Vec3> velocities;
  for (size_t i : objects.solids) {
    const JsonObject& sj = objects.all[i];
    FemSolid solid;
    solid.name = sj.string("name");
    solid.mesh = read_fem_mesh(sj.object("mesh"), top.file() + ": " + sj.path_of("mesh"), MeshUse::solid);
    if (model.solids.empty()) model.dim = solid.mesh.dim;
    if (solid.mesh.dim != model.dim) sj.fail("mesh", "all solids of a scene must be 2D (rectangle) or all 3D (box)");
    solid.material = read_fem_material(sj.object("material"));
    solid.volume = read_volume_treatment(sj, solid);
    velocities.push_back(sj.has("velocity") ? read_point(sj, "velocity", model.dim) : Vec3::Zero());
    add_fem_solid(model, std::move(solid));
    const Index index = static_cast<Index>(model.solids.size()) - 1;
    read_loads(sj, model, index);
    read_dirichlet(sj, model, index);
    sj.finish();
  }
  for (size_t i : objects.bodies) {
    const JsonObject& bj = objects.all[i];
    FemRigidBody rb;
    rb.name = bj.string("name");
    rb.mesh = read_fem_mesh(bj.object("mesh"), top.file() + ": " + bj.path_of("mesh"), MeshUse::solid);
    if (rb.mesh.dim != 3) bj.fail("mesh", "a rigid body's mesh is 3D (\"type\": \"box\")");
    rb.body = director_body_from_mesh(rb.mesh, bj.number("density", Range::positive()));
    rb.initial = director_state_at_rest_pose(rb.body, bj.vec3("velocity", Vec3::Zero()),
                                             bj.vec3("angular_velocity", Vec3::Zero()));
    bj.finish();
    problem.rigid_bodies.push_back(std::move(rb));
  }
  if (!problem.rigid_bodies.empty() && model.dim == 2)
    top.fail("objects", "rigid bodies are 3D; a scene with 2D (rectangle) solids cannot have them");
  if (!problem.rigid_bodies.empty() && problem.integrator == FemIntegrator::static_load_steps)
    objects.all[objects.bodies[0]].fail("kind", "rigid bodies need a dynamic integrator (\"midpoint\" or \"energy_momentum\")");
  problem.gravity = gravity;
  // Gravity acts on every solid as a body load rho g.
  if (gravity.head(model.dim).norm() > 0)
    for (const FemSolid& s : model.solids) {
      NodalLoad g{"gravity", {}, {}, [gravity](Real) { return gravity; }};
      for (Index n = s.node_begin; n < s.node_begin + s.mesh.node_count(); ++n) {
        g.nodes.push_back(n);
        g.weights.push_back(model.node_mass[n]);
      }
      model.loads.push_back(std::move(g));
    }
  finalize_fem_model(model);
  if (problem.integrator == FemIntegrator::static_load_steps && model.free_count > 0 && model.prescribed.empty())
    top.fail("objects", "a static solve needs Dirichlet conditions that hold the solids against rigid motion");
  problem.initial_velocity = VectorX::Zero(model.dof_count());
  for (size_t i = 0; i < model.solids.size(); ++i)
    for (Index n = 0; n < model.solids[i].mesh.node_count(); ++n)
      for (int k = 0; k < model.dim; ++k) problem.initial_velocity[model.dof(model.solids[i].node_begin + n, k)] = velocities[i][k];
  for (const JsonObject& joint : top.object_list("joints")) problem.joints.push_back(read_fem_joint(joint, problem));
  if (!problem.joints.empty() && problem.integrator == FemIntegrator::static_load_steps)
    top.fail("joints", "joints need a dynamic integrator (\"midpoint\" or \"energy_momentum\")");
  if (!problem.joints.empty() && problem.linear.petsc)
    top.fail("joints", "solids joined to rigid bodies are solved as one system by UMFPACK; \"linear_solver\": "
                       "{\"type\": \"petsc\"} is for solids without joints");
  for (const JsonObject& probe : top.object_list("probes")) problem.probes.push_back(read_fem_probe(probe, problem));
  // A distributed run (PETSc required above, joints refused with it): each rank assembles its part.
  if (const petsc_plugin::Communicator* ranks = mpi_world()) distribute_fem_model(model, *ranks);
}

}  // namespace moreau
