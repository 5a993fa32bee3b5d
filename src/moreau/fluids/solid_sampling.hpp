#pragma once
// Samples cloth and soft-body surfaces and continua for the fluid: the samples are boundary
// particles of the density constraint (like the collider walls of boundary_sampling.hpp) that
// move with the solid and carry the fluid's reaction back to it (solid_coupling.hpp).
//
// Cloth: every triangle is cut into n^2 similar sub-triangles, n = ceil(sqrt(2 A) / (2 r)), and a
// sample sits at each sub-triangle's centroid (no duplicates on shared edges; about two samples
// per (2r)^2 of area, so a sheet has no gap the fluid kernel, h = 4r, could see through). The
// sample's weights are its barycentric coordinates in the triangle. A sheet is sampled on its
// mid-surface: a cloth has no inside, and the fluid rests 2r from it on either side.
// Soft bodies: the boundary triangles are sampled the same way and each sample is moved r
// inwards along the face normal, where the next fluid lattice layer would be, as for colliders;
// its weights are the barycentric coordinates of that point in the tetrahedron holding it, so the
// fluid settles r from the actual surface and a floating body displaces its own volume.
// Continua: one sample per particle, at its centre, with the particle's rest volume.
// The other volumes are Akinci's (boundary_sampling.hpp), computed per object in the rest configuration and
// then kept: a sheet or surface that stretches keeps its samples' volumes.
#include "moreau/fluids/fluid_model.hpp"

namespace moreau {

struct Model;

/// Samples every cloth, soft body and continuum whose ObjectInfo::fluid_coupling is set, for a fluid of
/// particle radius r (spacing 2r) and kernel `kernel`. The model's particles and objects must be
/// final.
FluidSolidSamples sample_fluid_solids(const Model& model, Real particle_radius, const CubicSplineKernel& kernel);

}  // namespace moreau
