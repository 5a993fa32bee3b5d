#pragma once
// The Model: everything a scene builds that does not change during a run — particles' masses and
// rest positions, objects, colliders, constraint families (already colour-sorted) and settings.
// Every stage of a step takes (const Model&, State&).
#include <string>
#include <vector>

#include "moreau/collision/collider.hpp"
#include "moreau/constraints/compliant_contact.hpp"
#include "moreau/continuum/continuum_model.hpp"
#include "moreau/constraints/particle_families.hpp"
#include "moreau/constraints/suction_cavity.hpp"
#include "moreau/fluids/fluid_model.hpp"
#include "moreau/model/particle_emitter.hpp"
#include "moreau/rigid/joint_tree.hpp"
#include "moreau/constraints/joints/joint.hpp"
#include "moreau/rigid/rigid_bodies.hpp"
#include "moreau/rods/rod_model.hpp"
#include "moreau/shape_matching/shape_matching.hpp"
#include "moreau/solvers/nmd/nmd_settings.hpp"

namespace moreau {

enum class ObjectKind { collider, cloth, soft_body, fluid, rigid_body, rod, granular, shape_matched, continuum };

/// One named scene object. Particles of an object are the contiguous range [particle_begin, particle_end).
/// Fluid objects have no particles here: theirs live in FluidState (phase `fluid_phase`).
struct ObjectInfo {
  std::string name;
  ObjectKind kind = ObjectKind::cloth;
  Index particle_begin = 0, particle_end = 0;
  std::vector<std::array<Index, 3>> surface;  // global particle indices: cloth triangles / soft-body boundary
  std::vector<std::array<Index, 4>> tets;     // global particle indices (soft bodies)
  Index collider = -1;                        // index into Model::colliders (colliders only)
  Index fluid_phase = -1;                     // index into Model::fluid.phases (fluids only)
  Index body = -1;                            // index into Model::rigid (rigid bodies; colliders that rigid bodies touch;
                                              // a rod's first segment)
  Index body_count = 0;                       // rigid bodies: 1; rods: their segments
  Index rod = -1;                             // index into Model::rods (rods only)
  bool self_collision = false;                // particle contacts within the object
  bool fluid_coupling = true;                 // cloth, soft body, rigid body, continuum: a two-way boundary of the fluids
  Real fluid_friction = 0;                    // cloth, soft body, rigid body, continuum: the fluids' wall friction, [0, 1]
  Real static_friction = 0.5, dynamic_friction = 0.5, restitution = 0;
  Real adhesion = 0;                          // N per contact point under nmd: rigid contacts, and cloth and soft-body particles on bodies and colliders
  Real cohesion = 0;                          // granular: N, the largest pull of a bond between two grains
  Real cohesion_distance = 0;                 // granular: m, the gap at which a bond lets go
  Real rolling_resistance = 0;                // granular: mu_r, the rolling torque's bound in units of R* times the normal force
  ContactSpring contact_spring;               // granular: a viscoelastic contact's spring and dashpot (0: hard)
  Index clump_size = 0;                       // granular: spheres per clump (rigid shape-matching clusters, contiguous); 0: spheres

  Index particle_count() const { return particle_end - particle_begin; }
  bool has_particles() const { return particle_end > particle_begin; }
  /// Has simulated particles (in the model's particle arrays or, for fluids, in FluidState).
  bool is_simulated() const { return has_particles() || kind == ObjectKind::fluid || has_bodies(); }
  /// Moves as dynamic rigid bodies: a rigid body, or a rod's segments.
  bool has_bodies() const { return kind == ObjectKind::rigid_body || kind == ObjectKind::rod; }
};

// How the joints' equality rows are solved each iteration: the direct tree solver of Deul et al.
// 2018 (joint_tree.hpp) where the joint graph is a tree, or Gauss-Seidel over the joints.
enum class JointSolver { direct, gauss_seidel };

// Sleeping grains (sleeping/grain_sleep.hpp): an island of grains that has stayed slower than
// `speed` for `time` rests until something reaches it.
struct SleepSettings {
  bool enabled = false;                     // settings.sleep present
  Real speed = 0.01;                        // m/s
  Real time = 0.5;                          // s
};

// The continua under XPBI (solvers/xpbi/): Yu et al. 2024's XSPH coefficient and anti-clumping
// distance.
struct XpbiSettings {
  Real xsph = 0.01;          // c of the XSPH smoothing, once per substep (solvers/xpbi/continuum_update.hpp)
  Real min_distance = 0.75;  // in r: no two continuum particles come closer
  bool packing_volume = true;  // det F follows the particles' packing where they pack closer (continuum/packing_volume.hpp)
};

struct SolverSettings {
  Real dt = 1.0 / 60;                       // s, output-independent step
  int substeps = 20;
  int iterations = 1;
  Vec3 gravity = Vec3(0, -9.81, 0);         // m/s^2
  int threads = 0;                          // 0 = all cores
  bool particle_contacts = true;            // contacts between objects and cloth self-collision
  Real contact_margin_factor = 2.0;         // contact candidates within r_i + r_j + k dt |v_rel| (Mueller 2020: k = 2)
  Real max_speed = 1e3;                     // m/s; faster particles are reported as a numerical failure
  JointSolver joint_solver = JointSolver::direct;
  NmdSettings nmd;                          // the velocity-level formulation (settings.nmd)
  XpbiSettings xpbi;                        // the continua (settings.xpbi)
  SleepSettings sleep;                      // settings.sleep
};

struct Model {
  // Particles (one entry per simulated point).
  std::vector<Vec3> particle_rest_position;   // m
  std::vector<Real> particle_mass;            // kg (pinned particles keep their mass for probes)
  std::vector<Real> particle_inv_mass;        // 1/kg; 0 = pinned
  std::vector<Real> particle_inv_inertia;     // 1/(kg m^2): grains turn as solid spheres, 5/(2 m r^2); 0: does not turn
  std::vector<Real> particle_radius;          // m, collision radius for particle-particle contacts
  std::vector<Real> particle_collider_gap;    // m, distance kept from colliders
  std::vector<Index> particle_object;         // owning object
  std::vector<Index> contact_particle;        // particles that take part in particle-particle contacts

  std::vector<ObjectInfo> objects;
  std::vector<Collider> colliders;

  // Constraint families between particles (particle_families.hpp), colour-sorted at build time.
  ParticleFamilies constraints;

  FluidModel fluid;

  RigidBodyModel rigid;        // rigid bodies, then colliders as kinematic bodies
  std::vector<Joint> joints;
  std::vector<RodModel> rods;                 // rods: their segments are bodies of `rigid`, their junctions joints
  ShapeMatchClusters shape_matching;          // the clusters of shape-matched objects
  std::vector<ParticleEmitter> particle_emitters;  // granular and continuum objects' emitters: their particles exist from the start
  std::vector<SuctionCup> suction_cups;       // soft bodies with a sealed cavity (nmd only)
  ContinuumModel continuum;                   // the inelastic continua's particles and materials (xpbi only)
  JointForest joint_forest;                   // joints solved directly (empty for Gauss-Seidel)

  SolverSettings settings;

  Index particle_count() const { return static_cast<Index>(particle_inv_mass.size()); }
  /// Object index by name, or -1.
  Index find_object(const std::string& name) const;
  /// The end of the object's particles that exist from the start: the particles its emitter
  /// releases during the run come after (model/particle_emitter.hpp); joints and probes take only these.
  Index initial_particle_end(Index object) const;
  /// One family of `constraints`, e.g. family<DistanceConstraints>().
  template <class Family>
  Family& family() { return std::get<Family>(constraints); }
  template <class Family>
  const Family& family() const { return std::get<Family>(constraints); }
  /// Colours every family (call once after all constraints are added).
  void color_constraints();
};

}  // namespace moreau
