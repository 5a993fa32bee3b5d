#pragma once
// A loaded scene: the model, its initial state, and what the run should measure and write.
#include <string>
#include <vector>

#include <memory>

#include "moreau/fem/scene/fem_problem.hpp"
#include "moreau/io/frame_formats.hpp"
#include "moreau/io/probes.hpp"
#include "moreau/model/state.hpp"
#include "moreau/solvers/solver.hpp"

namespace moreau {

struct OutputSettings {
  int every = 1;          // write frames and probe rows every N steps
  FrameFormats formats;   // vtk: frames/*.vtu|vtp + <scene>.pvd; obj, ply: frames/*.obj, *.ply
  int checkpoint_every = 0;  // write checkpoint.bin every N steps (and at the end); 0: only when interrupted
};

struct Scene {
  std::string name;
  std::string file;
  // A hash of the scene's JSON (after --set) without what only shapes a run (duration, output,
  // threads, description): a checkpoint records it and a restart compares it. Empty for a scene
  // built in code.
  std::string fingerprint;
  std::string solver = "xpbd";
  Real duration = 1.0;  // s
  Model model;
  State state;
  OutputSettings output;
  std::vector<Probe> probes;
  std::unique_ptr<FemProblem> fem;  // "solver": "fem" scenes: the FEM engine's problem (model is then empty)
  std::unique_ptr<Solver> formulation;  // the registered solver named by settings.solver (constraint-engine scenes)
};

/// Reads, validates and builds a scene. `overrides` are "path=value" assignments applied to the
/// JSON before validation. Throws InputError on any problem; nothing is written.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});
/// The same for scene JSON text; `source` names it in messages, and relative mesh paths are
/// resolved against its directory (the working directory for a bare name).
Scene load_scene_text(const std::string& text, const std::string& source, const std::vector<std::string>& overrides = {});

}  // namespace moreau
