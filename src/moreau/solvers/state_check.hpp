#pragma once
// The check every formulation of the constraint engine runs at the end of a step: every position
// and velocity finite and no speed above settings.max_speed, else a NumericalError naming the
// step, the time, the object and the particle or body (the run stops with exit 3).
namespace moreau {

struct Model;
struct State;

void check_state(const Model& model, const State& state);

}  // namespace moreau
