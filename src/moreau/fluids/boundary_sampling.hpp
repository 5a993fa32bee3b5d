#pragma once
// Samples collider surfaces with wall particles for the fluid, after Akinci, Ihmsen, Akinci,
// Solenthaler, Teschner 2012 ("Versatile rigid-fluid coupling for incompressible SPH", sec. 3.1):
// one layer of samples whose volumes are normalised by their own sampling density,
//   V_b = V * S_flat / sum_k W(x_b - x_k)      (k: all samples within h, including b itself)
// where S_flat is that sum for a flat square layer at the fluid spacing d = 2r. Akinci's volume is
// 1 / sum_k W_bk; the factor V S_flat makes a flat, evenly sampled wall count exactly like one
// lattice layer of fluid (V_b = V) while keeping Akinci's correction for denser, sparser or
// overlapping sampling (edges, corners, curved shapes).
// The layer lies r inside the solid (behind the surface), where the next fluid lattice layer
// would be. Fluid particles are kept r in front of the surface (fluid_motion.hpp), so with the
// kernel support h = 4r = 2d a fluid particle at rest next to a flat wall sees exactly the lattice
// density: the one missing layer (at distance d) is replaced by the samples, and layers further
// out are beyond h. (Samples on the surface itself, as in Akinci's paper, over-count by ~50 % at
// this spacing and push the fluid off the wall by a whole layer.)
// Boxes are sampled face by face on a grid, spheres by a Fibonacci lattice, capsules by rings on
// the cylinder and Fibonacci caps; planes on a square patch (they are infinite; the patch covers
// `plane_center` +- `plane_half_size` in the plane).
#include <vector>

#include "moreau/collision/collider.hpp"
#include "moreau/fluids/fluid_model.hpp"

namespace moreau {

/// Samples (offsets from the collider position, world axes) of the collider surface moved `depth`
/// into the solid, at spacing <= `spacing`.
std::vector<Vec3> sample_collider_surface(const Collider& collider, Real spacing, Real depth, const Vec3& plane_center,
                                          Real plane_half_size);

/// How many samples sample_collider_surface gives, counted without making them (a double: a
/// scene's walls may ask for more than any integer holds).
double collider_surface_sample_count(const Collider& collider, Real spacing, Real depth, Real plane_half_size);

/// Akinci volumes V_b = V S_flat / sum_k W(x_b - x_k) of samples at `world` positions (all of
/// them count each other), for a fluid lattice of the given spacing (V = spacing^3).
std::vector<Real> akinci_volumes(const std::vector<Vec3>& world, Real spacing, const CubicSplineKernel& kernel);

/// Samples the given colliders r = spacing / 2 inside their solid and computes the volumes.
FluidBoundarySamples sample_fluid_walls(const std::vector<Collider>& colliders, const std::vector<Index>& sampled,
                                        Real spacing, const CubicSplineKernel& kernel, const Vec3& plane_center,
                                        Real plane_half_size);

}  // namespace moreau
