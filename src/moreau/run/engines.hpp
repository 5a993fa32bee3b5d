#pragma once
// The engines the run loop knows (engine_list.cpp chooses one per scene).
#include "moreau/run/engine.hpp"

namespace moreau {

/// A scene of the constraint engine: its registered Solver over the Model and State.
std::unique_ptr<Engine> make_constraint_engine(Scene& scene);
/// A FEM scene of solids, director rigid bodies and joints.
std::unique_ptr<Engine> make_solid_engine(Scene& scene);
/// A FEM scene with a fluid: the stabilized Navier-Stokes flow (steady or transient).
std::unique_ptr<Engine> make_flow_engine(Scene& scene);

}  // namespace moreau
