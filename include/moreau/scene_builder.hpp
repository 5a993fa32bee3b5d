#pragma once
// moreau::SceneBuilder: a constraint-engine scene built in code, object by object. Every spec
// below is one entry of the scene format (docs/scene-format.md) with the same field names,
// defaults, units (SI) and checks: the scene loader reads a file into these specs and hands them
// to the same builder, so a scene built here and the same scene read from JSON are the same
// model, bit for bit. Plain types only (arrays of doubles, strings, optionals, variants), so a
// binding maps them field by field.
//
//   moreau::SceneBuilder scene("drop");
//   scene.settings().duration = 2.0;
//   scene.add(moreau::ColliderSpec{.name = "floor", .shape = moreau::PlaneShape{}});
//   scene.add(moreau::RigidBodySpec{.name = "box", .shape = moreau::BoxShape{{0.1, 0.1, 0.1}},
//                                   .position = moreau::Vector3{0, 1, 0}});
//   moreau::World world = scene.build();
//
// build() checks every spec and throws InputError naming the scene, the entry and the field
// ("scene 'drop': objects[1].mass: -1 is out of range; allowed: > 0").
#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "moreau/world.hpp"

namespace moreau {

using Vector2 = std::array<double, 2>;
using Vector3 = std::array<double, 3>;
using Quaternion = std::array<double, 4>;  // w, x, y, z

// ---- Settings -------------------------------------------------------------------------------

/// settings.fluid: the particle fluid's solver constants. Unset fields keep the engine defaults.
struct FluidSolverSettings {
  std::optional<double> neighbor_skin;  // fraction of the kernel radius the neighbour lists reach beyond it, [0, 1]
  std::optional<double> tensile_k;      // artificial pressure strength, [0, 10]
  std::optional<double> cfl_limit;      // largest particle travel per step, in particle radii
  std::string viscosity_solver = "auto";  // "auto", "explicit" or "implicit"
  std::optional<double> viscosity_tolerance;   // implicit: relative residual, (0, 1)
  std::optional<int> viscosity_iterations;     // implicit: BiCGSTAB iterations at most per solve
  std::optional<bool> phase_drift;             // a lighter liquid's particles under a heavier one's trade places with them
};

/// settings.nmd: the velocity-level formulation's constants. Unset fields keep the engine defaults.
struct NmdSolverSettings {
  std::string method = "pgs";                   // "pgs", "direct" or "hybrid"
  std::optional<int> substeps;                  // velocity solves per dt
  std::optional<int> iterations;                // projected Gauss-Seidel sweeps per solve
  std::optional<double> over_relaxation;        // omega, (0, 2)
  std::optional<double> tolerance;              // N s, hybrid: largest impulse change to stop at
  std::optional<double> stabilization;          // d, relaxation of hard rows in steps, >= 0
  std::string friction = "cone";                // "cone" or "box"
  std::optional<double> restitution_threshold;  // m/s
  std::optional<double> sliding_speed;          // m/s
  std::optional<double> contact_compliance;     // m/N
  std::optional<bool> warm_start;
};

/// settings.sleep: grains that stay slow rest until something reaches them. Unset fields keep
/// the engine defaults.
struct SleepSolverSettings {
  std::optional<double> speed;  // m/s: a grain slower than this is still
  std::optional<double> time;   // s: an island still this long falls asleep
};

/// settings.xpbi: the continua's smoothing and spacing (`"solver": "xpbi"`). Unset fields keep
/// the engine defaults.
struct XpbiSolverSettings {
  std::optional<double> xsph;          // c of the XSPH velocity smoothing per substep
  std::optional<double> min_distance;  // in particle spacings: the anti-clumping distance
  std::optional<bool> packing_volume;  // F's volume follows the particles' packing where it is closer
};

/// "settings". Unset fields keep the engine defaults listed in docs/scene-format.md.
struct SceneSettings {
  std::string solver = "xpbd";          // a registered constraint-engine formulation
  std::optional<double> dt;             // s
  std::optional<double> duration;       // s
  std::optional<Vector3> gravity;       // m/s^2
  std::optional<int> threads;           // 0 = all cores
  std::optional<int> substeps;
  std::optional<int> iterations;
  std::optional<bool> particle_contacts;
  std::optional<double> max_speed;      // m/s
  std::string joint_solver = "direct";  // "direct" or "gauss_seidel"
  FluidSolverSettings fluid;
  NmdSolverSettings nmd;
  XpbiSolverSettings xpbi;
  std::optional<SleepSolverSettings> sleep;  // absent: grains never sleep
  int output_every = 1;                 // output.every: frames and probe rows every N steps
  bool write_vtk = true;                // output.formats contains "vtk": frames/*.vtu|vtp and <scene>.pvd
  bool write_obj = false;               // ... "obj": frames/*.obj of the surfaces (cloth, soft and rigid bodies, colliders)
  bool write_ply = false;               // ... "ply": frames/*.ply of the particles with their arrays
  int checkpoint_every = 0;             // output.checkpoint_every: a checkpoint every N steps (0: none)
};

// ---- Shared pieces --------------------------------------------------------------------------

/// "friction" and "restitution".
struct ContactMaterial {
  double static_friction = 0.5;   // mu_s
  double dynamic_friction = 0.5;  // mu_k
  double restitution = 0;         // e, in [0, 1]
  double adhesion = 0;            // N per contact point, >= 0 ("nmd" only; rigid bodies and colliders)
};

/// One entry of "pin": particles of the object inside a region are held in place, rigidly
/// (compliance 0) or by a spring of the given compliance (m/N) and damping.
struct PinBox {
  Vector3 min{}, max{};
};
struct PinSphere {
  Vector3 center{};
  double radius = 0;
};
using PinVertices = std::vector<int>;
struct PinSpec {
  std::variant<PinBox, PinSphere, PinVertices> region;
  double compliance = 0;  // m/N
  double damping = 0;     // s
};

// Shapes of colliders ("shape" of a collider: plane, box, sphere, capsule) and of rigid bodies
// ("shape" of a rigid body: box, sphere, capsule, cylinder, convex_hull, triangle_mesh).
struct PlaneShape {
  Vector3 normal{0, 1, 0};
  Vector3 point{0, 0, 0};  // m, a point on the plane ("offset" d in a scene file is the point d n)
};
struct BoxShape {
  Vector3 half_extents{};  // m
};
struct SphereShape {
  double radius = 0;  // m
};
struct CapsuleShape {  // along the local y axis
  double radius = 0, half_height = 0;  // m
};
struct CylinderShape {  // along the local y axis
  double radius = 0, half_height = 0;  // m
};
struct ConvexHullShape {  // the convex hull of an OBJ file's vertices
  std::string mesh;
  double scale = 1;
};
struct TriangleMeshShape {  // an OBJ surface, one-sided, with a slab of solid behind each triangle
  std::string mesh;
  double scale = 1;
  double thickness = 0.05;  // m
};
using ShapeSpec =
    std::variant<PlaneShape, BoxShape, SphereShape, CapsuleShape, CylinderShape, ConvexHullShape, TriangleMeshShape>;

// ---- Objects --------------------------------------------------------------------------------

/// "kind": "collider": a fixed or kinematic shape that everything else collides with.
struct ColliderSpec {
  std::string name;
  ShapeSpec shape = PlaneShape{};    // plane, box, sphere or capsule
  Vector3 center{};                  // m (box, sphere, capsule)
  Vector3 rotation_deg{};            // about world x, then y, then z (box, capsule)
  Vector3 velocity{};                // m/s, a constant translation
  bool inside = false;               // a container: things stay inside the shape
  bool fluid_walls = true;           // sampled as a wall of the particle fluids
  double fluid_friction = 0;         // [0, 1]: 0 the fluid slips freely along the wall, 1 no slip
  std::optional<double> temperature;  // K: the wall holds the thermal fluids at its surface at it; none: insulating
  std::optional<double> until;       // s: the collider is removed at this time (a gate opened)
  ContactMaterial contact;
};

/// A cloth or soft-body mesh read from a file, scaled then translated.
struct MeshFile {
  std::string file;  // relative paths: against the scene file's folder (the working directory in code)
  double scale = 1;
  Vector3 translate{};
};

/// Cloth meshes: a grid sheet in the xz plane, an OBJ file, or triangles given in code.
struct GridSheet {
  Vector2 size{};                    // m, along x and z
  std::array<int, 2> resolution{};   // vertices along x and z, each >= 2
  Vector3 center{};
  Vector3 rotation_deg{};            // about the sheet's centre
};
struct TriangleList {
  std::vector<Vector3> vertices;     // m
  std::vector<std::array<int, 3>> triangles;
};
using ClothMesh = std::variant<GridSheet, MeshFile, TriangleList>;

struct ClothMaterial {
  std::optional<double> area_density;       // kg/m^2; or
  std::optional<double> vertex_mass;        // kg per vertex
  double damping = 0;                       // s, Rayleigh-like damping of every constraint
  std::optional<double> youngs_modulus;     // Pa: a membrane (triangle strain) with
  std::optional<double> poisson_ratio;      //   (-1, 0.5), default 0.3
  std::optional<double> thickness;          //   m
  std::optional<double> stretch_compliance; // m/N: edge springs instead of a membrane
  std::optional<double> bending_stiffness;  // N m; or
  std::optional<double> bend_compliance;    // 1/(N m)
  std::string bending_model = "dihedral";   // "dihedral" or "isometric"
};

struct ClothSpec {
  std::string name;
  ClothMesh mesh;
  ClothMaterial material;
  std::optional<double> collision_radius;   // m; default half the mean edge length
  std::optional<double> collider_gap;       // m; default the collision radius
  Vector3 velocity{};
  bool self_collision = true;
  bool fluid_coupling = true;
  double fluid_friction = 0;                // the particle fluids' wall friction at the sheet: 0 free slip, 1 no slip
  ContactMaterial contact;
  std::vector<PinSpec> pin;
};

/// Soft-body meshes: a box of cells, a tetrahedral mesh file, an OBJ surface filled with
/// tetrahedra, or tetrahedra given in code.
struct TetBox {
  Vector3 min{}, max{};              // m
  std::array<int, 3> cells{};        // along x, y, z, each >= 1
  int tets_per_cell = 6;             // 5 or 6
};
struct TetMeshFile {
  std::string format;                // "msh" (Gmsh 4) or "tetgen" (file is the base name of .node and .ele)
  MeshFile file;
};
struct TetrahedralizedObj {
  MeshFile file;
  double quality = 1.5;              // radius-edge ratio bound, [1.1, 10]
  double max_volume = 0;             // m^3, 0: no bound
};
struct TetList {
  std::vector<Vector3> vertices;     // m
  std::vector<std::array<int, 4>> tets;
};
using SoftBodyMesh = std::variant<TetBox, TetMeshFile, TetrahedralizedObj, TetList>;

struct SoftBodyMaterial {
  std::string model = "neo_hookean";        // or "st_venant_kirchhoff" (Green-strain rows)
  std::optional<double> youngs_modulus;     // Pa
  std::optional<double> poisson_ratio;      // (-1, 0.5)
  std::optional<double> density;            // kg/m^3
  double damping = 0;                       // s
  std::optional<double> volume_compliance;  // m^3/N: an extra volume constraint per tetrahedron
};

/// A soft body as a suction cup (the velocity-level formulation only): its boundary faces that
/// look along `opening` at rest, except those lying in the mouth (the flat rim), are the cavity.
struct SuctionSpec {
  Vector3 opening{};                     // the direction the cup's mouth faces at rest
  double atmospheric_pressure = 101325;  // Pa
  double seal_gap = 1e-3;                // m a rim vertex may lift beyond its contact before air leaks in
};

struct SoftBodySpec {
  std::string name;
  SoftBodyMesh mesh;
  SoftBodyMaterial material;
  std::optional<double> collision_radius;   // m; default half the mean boundary edge length
  double collider_gap = 0;                  // m
  Vector3 velocity{};                       // m/s
  Vector3 angular_velocity{};               // rad/s, about the centre of mass
  bool self_collision = false;
  bool fluid_coupling = true;
  double fluid_friction = 0;                // the particle fluids' wall friction at its surface: 0 free slip, 1 no slip
  ContactMaterial contact;
  std::vector<PinSpec> pin;
  std::optional<SuctionSpec> suction;
};

struct FluidBlock {
  Vector3 min{}, max{};  // m
};

/// An "emitter" of a fluid or a granular object: an opening (a disc or a rectangle of lattice
/// points) that releases a layer of particles each time the flow has advanced one spacing.
struct EmitterSpec {
  std::string shape = "disc";        // "disc" (radius) or "rectangle" (size, tangent)
  Vector3 center{};                  // m
  Vector3 direction{};               // the flow direction
  double radius = 0;                 // m (disc)
  Vector2 size{};                    // m (rectangle)
  Vector3 tangent{};                 // the rectangle's first side; zero: any
  std::optional<double> speed;       // m/s; or
  std::optional<double> flow_rate;   // m^3/s (fluids, continua); or
  double start = 0;                  // s
  std::optional<double> stop;        // s; default the scene's duration
  std::optional<double> mass_rate;   // kg/s (grains, continua), instead of speed
  std::optional<double> nozzle_length;  // m (fluids, continua): the stream is held at `speed` this far past the
                                        // opening; default one kernel support (fluids 4r, continua 2r)
};
using FluidEmitterSpec = EmitterSpec;

/// A fluid's "thermal" entry: its temperature, and how it conducts heat, melts and freezes.
struct FluidThermalSpec {
  double temperature = 293.15;            // K, of the initial and emitted particles
  double conductivity = 0.6;              // W/(m K) (water)
  double specific_heat = 4186;            // J/(kg K) (water), the same solid and liquid
  std::optional<double> melting_point;    // K; none: liquid at every temperature
  double latent_heat = 0;                 // J/kg, with a melting point
  std::optional<double> solid_viscosity;  // Pa s, as a particle begins to melt; default: the fluid's viscosity
  double expansion = 0;                   // 1/K, volumetric thermal expansion (buoyancy); 0: none
  std::optional<double> reference_temperature;  // K, where the fluid has its density; needed with an expansion
};

/// A fluid's "gas" entry: the fluid is a gas in open air of its own density (smoke, steam). The air
/// carries its weight, so only its buoyancy acts (with a thermal expansion), and it drags the
/// particles that it partly surrounds toward the wind.
struct FluidGasSpec {
  double drag = 10;   // 1/s, k: the air's drag on a particle with no neighbours is k (1 - 1/pi) (v - wind)
  Vector3 wind{};     // m/s, the air's velocity
  double mixing = 0;  // 1/s, m: the air dilutes a lone particle's smoke (and heat, with an expansion) at m (1 - 1/pi)
};

/// "kind": "fluid": particles on a lattice of spacing 2 r filling a block, blocks or a closed OBJ
/// surface, and/or released by an emitter.
/// The tension of the interface between a fluid and another liquid of the scene (interfacial_tension.hpp).
struct FluidInterfaceSpec {
  std::string fluid;   // the other fluid's name
  double tension = 0;  // N/m
};

struct FluidSpec {
  std::string name;
  std::optional<double> particle_radius;  // m, the same for every fluid of the scene
  double density = 1000;             // kg/m^3
  double viscosity = 1.0e-3;         // Pa s
  double xsph = 0.01;                // [0, 1]
  double vorticity = 0;              // m/s
  double surface_tension = 0;        // N/m, gamma against air
  std::optional<double> contact_angle_deg;  // degrees, on the colliders (needs surface_tension); none: 180
  std::vector<FluidInterfaceSpec> interfacial_tension;  // against other liquids; none given: 0
  double relaxation = 0.01;          // [0, 1e6]
  double bulk_modulus = 2.2e9;       // Pa, K of the density rows under "nmd" (water: 2.2e9)
  std::optional<FluidBlock> block;
  std::vector<FluidBlock> blocks;
  std::string mesh;                  // a closed OBJ surface to fill
  Vector3 velocity{};                // m/s
  std::optional<FluidEmitterSpec> emitter;
  std::optional<FluidThermalSpec> thermal;  // none: the fluid carries no heat
  std::optional<FluidGasSpec> gas;          // none: a liquid, or a gas filling its container
};

/// "kind": "rigid_body".
struct RigidBodySpec {
  std::string name;
  ShapeSpec shape = SphereShape{};        // box, sphere, capsule, cylinder, convex_hull, triangle_mesh
  std::optional<double> mass;             // kg; or
  std::optional<double> density;          // kg/m^3 (default 1000)
  bool fixed = false;
  bool kinematic = false;
  std::optional<Vector3> position;        // m, of the shape's own origin
  std::optional<Quaternion> orientation;  // w, x, y, z (normalised); or
  Vector3 rotation_deg{};                 // about world x, then y, then z
  Vector3 velocity{};                     // m/s, of the shape's origin
  Vector3 angular_velocity{};             // rad/s
  ContactMaterial contact;
  bool fluid_coupling = true;
  double fluid_friction = 0;              // the particle fluids' wall friction at its surface: 0 free slip, 1 no slip
};

/// A rod's centreline at rest: a helix about `axis` through `center` (the start lies at
/// center + radius along a direction across the axis), rising `pitch` per turn.
struct RodHelix {
  Vector3 center{};                       // m, on the axis at the start's height
  Vector3 axis{0, 1, 0};                  // the direction it rises along
  double radius = 0;                      // m
  double pitch = 0;                       // m per turn (0: a circle's arc)
  double turns = 1;
};

/// "kind": "rod": a Cosserat rod of rigid segments joined by bend-twist and stretch-shear
/// constraints (docs/scene-format.md, "Rods").
struct RodSpec {
  std::string name;
  std::vector<Vector3> points;            // m, a polyline at rest; or
  std::optional<RodHelix> helix;
  std::optional<int> segments;            // default: one per polyline edge, 16 per helix turn
  std::optional<Vector3> normal;          // the section's first axis at the start (default: any across the rod)
  std::optional<double> radius;           // m, a round section; or
  std::optional<Vector2> radii;           // m, an elliptic section: along the first axis, along the second
  std::optional<double> youngs_modulus;   // Pa, E (required)
  std::optional<double> shear_modulus;    // Pa, G; or
  std::optional<double> poisson_ratio;    // G = E / (2 (1 + nu)), default nu = 0.3
  std::optional<double> bending_modulus;  // Pa, the E of bending (default: youngs_modulus)
  double density = 1000;                  // kg/m^3
  std::string start = "free", end = "free";  // "free", "clamped" or "pinned" to the world where it is
  double damping_time = 0;                // s, Kelvin-Voigt: the strain rates' stress is damping_time times the stiffness
  Vector3 velocity{};                     // m/s
  ContactMaterial contact;
  bool self_collision = true;
};

/// A vertical cylinder (its axis along y) to fill, e.g. a column released on the ground.
struct FilledCylinder {
  Vector3 base{};      // m, the centre of its bottom face
  double radius = 0;   // m
  double height = 0;   // m
};

/// A ball to fill, e.g. a snowball.
struct FilledSphere {
  Vector3 center{};    // m
  double radius = 0;   // m
};

/// What a granular object or a continuum fills, any together: boxes ("blocks"), vertical
/// "cylinders", "spheres" and the inside of a closed OBJ surface ("mesh").
struct FilledRegions {
  std::vector<FluidBlock> blocks;         // m
  std::vector<FilledCylinder> cylinders;  // m
  std::vector<FilledSphere> spheres;      // m
  std::string mesh;                       // the path of a closed OBJ surface
  bool empty() const { return blocks.empty() && cylinders.empty() && spheres.empty() && mesh.empty(); }
};

/// A granular object's clumps: each grain a rigid cluster of overlapping spheres of its radius.
struct GranularClump {
  int spheres = 2;        // 2 (a pair), 3 (a triangle) or 4 (a tetrahedron)
  double spacing = 1.0;   // the spheres' centre distance in radii, in (0, 2)
};

/// "kind": "granular": grains (spheres) on a lattice filling regions, each a particle
/// that touches the others, the colliders, rigid bodies and rods with friction and restitution
/// (docs/scene-format.md, "Granular media").
struct GranularSpec {
  std::string name;
  FilledRegions regions;                  // what the grains fill (or an emitter pours them)
  std::optional<double> radius;           // m, one radius; or
  std::optional<Vector2> radius_range;    // m, radii drawn uniformly from [min, max] (polydisperse)
  int seed = 1;                           // of the radius draws
  double density = 2600;                  // kg/m^3 of a grain
  Vector3 velocity{};                     // m/s
  ContactMaterial contact;
  double cohesion = 0;                    // N, the largest pull of a bond between two touching grains
  std::optional<double> cohesion_distance;  // m, the gap at which a bond lets go (default r_max / 10)
  double rolling_resistance = 0.5;        // mu_r: a contact's rolling torque is at most mu_r R* times its normal force
  double contact_compliance = 0;          // m/N, 1/k of a contact's spring (0: hard contacts)
  double contact_damping = 0;             // N s/m, the dashpot beside the spring (only with contact_compliance)
  std::optional<EmitterSpec> emitter;     // grains released through an opening during the run
  std::optional<GranularClump> clump;     // grains as rigid clumps of spheres (shape matching)
};

/// "kind": "shape_matched": particles on a lattice filling boxes, held in their rest shape by
/// shape matching over overlapping clusters (docs/scene-format.md, "Shape matching").
struct ShapeMatchedSpec {
  std::string name;
  std::vector<FluidBlock> blocks;           // m, boxes the particles fill
  double radius = 0;                        // m, of a particle (the lattice spacing is 2 r)
  double density = 1000;                    // kg/m^3 of the filled volume
  std::optional<double> frequency;          // Hz: how fast a particle pulled off its goal returns; absent: rigid
  std::optional<double> cluster_radius;     // m: particles within it of a cluster centre join it; absent: one cluster
  std::optional<double> cluster_spacing;    // m: cluster centres on a lattice (default: the cluster radius)
  Vector3 velocity{};                       // m/s
  ContactMaterial contact;
};

/// A continuum's plastic flow: "drucker_prager" (sand), "von_mises" (metal, plasticine), "snow"
/// (Stomakhin et al. 2013), "herschel_bulkley" (foam, cream, mud, paste; Bingham for flow index
/// 1) or "maxwell" (a viscoelastic fluid: silly putty, slime); absent, the continuum is an elastic
/// StVK-Hencky solid.
struct ContinuumPlasticity {
  std::string model;                         // drucker_prager, von_mises, snow, herschel_bulkley, maxwell
  std::optional<double> friction_angle_deg;  // drucker_prager (required), degrees
  double cohesion = 0;                       // drucker_prager: Pa, the isotropic tension it carries
  std::optional<double> yield_stress;        // von_mises (required): Pa, uniaxial
  double critical_compression = 0.025;       // snow: theta_c (Stomakhin et al. 2013)
  double critical_stretch = 0.0075;          // snow: theta_s
  double hardening = 10;                     // snow: xi
  std::optional<double> shear_yield_stress;  // herschel_bulkley (required): Pa, tau_y in simple shear
  std::optional<double> consistency;         // herschel_bulkley (required): Pa s^n, K
  double flow_index = 1;                     // herschel_bulkley: n (1: Bingham)
  std::optional<double> relaxation_time;     // maxwell (required): s, lambda; shear viscosity mu lambda
};

/// "kind": "continuum": an inelastic (or elastic) continuum of particles on a cubic lattice of
/// spacing r filling regions, simulated by XPBI (`"solver": "xpbi"`)
/// (docs/scene-format.md, "Continua").
struct ContinuumSpec {
  std::string name;
  FilledRegions regions;                    // what the particles fill (or an emitter pours them)
  std::optional<EmitterSpec> emitter;       // pours particles through an opening during the run
  double spacing = 0;                       // m, r (required)
  double density = 1000;                    // kg/m^3
  std::optional<double> youngs_modulus;     // Pa, E (required)
  double poisson_ratio = 0.3;               // nu in (-1, 0.5)
  std::optional<ContinuumPlasticity> plasticity;
  Vector3 velocity{};                       // m/s
  ContactMaterial contact;                  // against colliders and other objects
  bool fluid_coupling = true;               // the particles are a two-way boundary of the fluids
  double fluid_friction = 0;                // the particle fluids' wall friction at its particles: 0 free slip, 1 no slip
};

using ObjectSpec = std::variant<ColliderSpec, ClothSpec, SoftBodySpec, FluidSpec, RigidBodySpec, RodSpec, GranularSpec,
                                ShapeMatchedSpec, ContinuumSpec>;

// ---- Joints ---------------------------------------------------------------------------------

/// One end of a joint: "world", a rigid body's name, or one particle of a cloth or soft body
/// (by vertex index or the vertex nearest a point).
struct JointEndSpec {
  std::string object = "world";
  std::optional<int> vertex;
  std::optional<Vector3> nearest;
};

struct JointDrive {
  std::optional<double> target_angle_deg;  // hinge; or
  std::optional<double> target_position;   // m, prismatic; or
  std::optional<double> target_velocity;   // rad/s or m/s
  double max_force = 0;                    // N (prismatic) or N m (hinge); 0: unbounded
  double compliance = 0;
};

struct JointSpec {
  std::string name;
  std::string type;                          // fixed, spherical, hinge, prismatic, distance
  std::array<JointEndSpec, 2> bodies;
  std::optional<Vector3> anchor;             // m, one world point; or
  std::optional<std::array<Vector3, 2>> anchors;  // one per end
  Vector3 axis{1, 0, 0};
  double compliance = 0, angular_compliance = 0, damping = 0, angular_damping = 0;
  std::optional<Vector2> limits_deg;         // hinge
  std::optional<Vector2> limits;             // m, prismatic
  std::optional<double> swing_deg;           // spherical, [0, 180]
  std::optional<Vector2> twist_deg;          // spherical
  std::optional<double> min, max;            // m, distance; default the rest distance
  std::optional<JointDrive> drive;           // hinge, prismatic
  bool collide = false;                      // the joined bodies still collide
};

// ---- Probes ---------------------------------------------------------------------------------

/// One column group of probes.csv (docs/scene-format.md, "Probes"). Fields a type does not use
/// are ignored.
struct ProbeSpec {
  std::string name;
  std::string type;                  // point, energy, center_of_mass, extent, momentum, ...
  std::string object;                // an object's name, or "*" for every object where allowed
  std::string joint;                 // joint_error: a joint's name or "*"
  std::string quantity;              // empty: the type's default
  std::optional<int> vertex;         // point: a vertex of the object; or
  std::optional<Vector3> nearest;    // point: the vertex nearest this rest position, m
  std::string axis;                  // extent: x, y or z
  Vector3 about{};                   // momentum: the reference point of angular momentum, m
  std::optional<Vector3> at;         // fluid_height: a point on the vertical line measured, m
  std::optional<FluidBlock> box;     // escaped: particles outside this box are counted
  std::string family = "all";        // constraint_error: one family or all
  std::optional<Vector3> center;     // angle_of_repose: a point on the pile's axis, m
  std::optional<double> bin;         // angle_of_repose: width of the rings the surface is binned in, m
  std::optional<double> resting_speed;  // angle_of_repose: only particles slower than this count, m/s
  std::optional<Vector3> direction;  // runout: measure along this horizontal direction from `center` (else radially)
  std::optional<double> fraction;    // runout: the share of the particles within the runout (default 0.99)
  std::optional<Vector3> point;      // mass_flow: a point on the plane, m
  std::optional<Vector3> normal;     // mass_flow: the plane's normal (the positive direction)
};

// ---- The builder ----------------------------------------------------------------------------

class SceneBuilder {
 public:
  explicit SceneBuilder(std::string name);
  SceneSettings& settings() { return settings_; }
  SceneBuilder& add(ObjectSpec object);
  SceneBuilder& add(JointSpec joint);
  SceneBuilder& add(ProbeSpec probe);
  /// Checks every spec and builds the world; relative mesh paths are resolved against the
  /// working directory. Throws InputError on the first problem.
  World build() const;

 private:
  std::string name_;
  SceneSettings settings_;
  std::vector<ObjectSpec> objects_;
  std::vector<JointSpec> joints_;
  std::vector<ProbeSpec> probes_;
};

}  // namespace moreau
