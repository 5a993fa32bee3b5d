#pragma once
// Reading "solver": "fem" scenes (build_fem.cpp).
#include "moreau/fem/fem_problem.hpp"
#include "moreau/scene/json_reader.hpp"

namespace moreau {

/// The FEM keys of "settings": integrator and newton.
void read_fem_settings(const JsonObject& settings, FemProblem& problem);

/// "solids", "rigid_bodies" and "probes" of a FEM scene; gravity (m/s^2) becomes a body load on
/// every solid and a force m g on every rigid body.
void build_fem_scene(const JsonObject& top, FemProblem& problem, const Vec3& gravity, int threads);

}  // namespace moreau
