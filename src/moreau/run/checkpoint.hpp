#pragma once
// Checkpoint files: an engine's whole state at the end of one step, written so that a run can
// stop and resume bit for bit (`moreau run scene.json --restart FILE`).
//
// Layout (version 1, little-endian as in memory):
//   "moreau-checkpoint\n"   magic, 18 bytes
//   uint32                  format version
//   uint64 + bytes          the header (CheckpointHeader, archived field by field)
//   uint64 + bytes          the engine's state (Engine::save_state)
//   uint64                  FNV-1a hash of the header and state bytes (detects damage)
// The file is written to "<path>.part" and renamed into place, so it is whole or absent.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "moreau/io/pvd_collection.hpp"

namespace moreau {

class Engine;
struct Scene;

/// What identifies a checkpoint's scene and run, before the state itself.
struct CheckpointHeader {
  std::string moreau_version;
  std::string scene;              // the scene's name
  std::string scene_fingerprint;  // Scene::fingerprint: the scene's JSON without duration, output, threads
  std::string engine;             // Engine::name()
  std::vector<std::string> layout;  // "<array>:<components>x<count>" for each state array, "<object>:<kind>:<count>" each object
  double time = 0;                // s
  std::int64_t steps = 0;         // steps from the scene's start
  std::string out_dir;            // the absolute output directory of the run that wrote it
  FrameSeries frames;             // the frames that run had written
  std::vector<std::pair<std::string, std::uint64_t>> appended_files;  // files it appends rows to, and their sizes then
};

/// The header fields that identify `scene` as `engine` holds it now (version, names,
/// fingerprint, layout); the run fields are left for the caller.
CheckpointHeader checkpoint_identity(const Scene& scene, Engine& engine);

/// Writes the checkpoint (atomically).
void write_checkpoint(const std::string& path, const CheckpointHeader& header, const Engine& engine);

/// Reads the checkpoint at `path` into `engine` after checking that it was written for the scene
/// `identity` describes; InputError naming the file and what differs (another scene, another
/// engine, another layout, a damaged or truncated file, another format version). On error the
/// engine is left as it was.
CheckpointHeader read_checkpoint(const std::string& path, const CheckpointHeader& identity, Engine& engine);

}  // namespace moreau
