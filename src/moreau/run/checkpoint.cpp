#include "moreau/run/checkpoint.hpp"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "moreau/errors.hpp"
#include "moreau/io/atomic_file.hpp"
#include "moreau/io/binary_archive.hpp"
#include "moreau/math/fnv1a.hpp"
#include "moreau/moreau.hpp"
#include "moreau/run/engine.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {

namespace {

constexpr char kMagic[] = "moreau-checkpoint\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;
// 2: a flow with immersed solids also stores its rigid bodies' frames and their velocities.
// 3: and the fluid's force and torque on each rigid body over the last step.
// 4: the fluid's force on every immersed solid and the solids' forces on the fluid over the last step.
// 5: each fluid particle's enthalpy and viscosity (fluid_heat.hpp).
// 6: each fluid particle's smoke concentration (ambient_air.hpp).
// 7: the solids' Krylov counters and their CG-to-GMRES switch.
// 8: when each fluid particle held in an emitter's nozzle goes free (fluid_emitter.hpp).
// 9: the particle emitters' freed layers and held particles (model/particle_emitter.hpp).
constexpr std::uint32_t kFormatVersion = 9;

// The checksum of a checkpoint's header and state.
std::uint64_t checksum(const std::string& header, const std::string& state) { return fnv1a(state, fnv1a(header)); }

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// The first differing entries of two layouts, for the message.
std::string layout_difference(const std::vector<std::string>& file, const std::vector<std::string>& scene) {
  for (std::size_t i = 0; i < std::max(file.size(), scene.size()); ++i) {
    const std::string a = i < file.size() ? file[i] : "(nothing)", b = i < scene.size() ? scene[i] : "(nothing)";
    if (a != b) return fmt::format("the checkpoint has {} where the scene has {}", a, b);
  }
  return "";
}

}  // namespace

CheckpointHeader checkpoint_identity(const Scene& scene, Engine& engine) {
  CheckpointHeader h;
  h.moreau_version = version();
  h.scene = scene.name;
  h.scene_fingerprint = scene.fingerprint;
  h.engine = engine.name();
  for (const StateArray& a : engine.state_arrays()) h.layout.push_back(fmt::format("{}:{}x{}", a.name, a.components, a.count));
  for (const WorldObject& o : engine.objects()) h.layout.push_back(fmt::format("{}:{}:{}", o.name, o.kind, o.count));
  return h;
}

void write_checkpoint(const std::string& path, const CheckpointHeader& header, const Engine& engine) {
  ArchiveWriter head, state;
  archive(head, header);
  engine.save_state(state);
  std::string bytes(kMagic, kMagicSize);
  put(bytes, kFormatVersion);
  put(bytes, static_cast<std::uint64_t>(head.buffer().size()));
  bytes += head.buffer();
  put(bytes, static_cast<std::uint64_t>(state.buffer().size()));
  bytes += state.buffer();
  put(bytes, checksum(head.buffer(), state.buffer()));
  write_file_atomically(path, bytes);
}

CheckpointHeader read_checkpoint(const std::string& path, const CheckpointHeader& identity, Engine& engine) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("--restart {}: cannot open the checkpoint file", path));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto fail = [&](const std::string& what) { return InputError(fmt::format("--restart {}: {}", path, what)); };
  if (bytes.size() < kMagicSize || bytes.compare(0, kMagicSize, kMagic) != 0)
    throw fail("not a moreau checkpoint (it does not start with \"moreau-checkpoint\"); give a checkpoint.bin a run wrote");

  ArchiveReader file(bytes.data() + kMagicSize, bytes.size() - kMagicSize);
  std::string head_bytes, state_bytes;
  std::uint64_t stored_hash = 0;
  std::uint32_t format = 0;
  try {
    file.bytes(&format, sizeof format);
    if (format != kFormatVersion)
      throw fail(fmt::format("checkpoint format {} is not the one this moreau ({}) reads ({}); resume it with the moreau that "
                             "wrote it",
                             format, version(), kFormatVersion));
    unarchive(file, head_bytes);
    unarchive(file, state_bytes);
    file.bytes(&stored_hash, sizeof stored_hash);
  } catch (const ArchiveError&) {
    throw fail("the file is truncated (the run that wrote it may have been killed while writing it)");
  }
  if (file.remaining() != 0 || stored_hash != checksum(head_bytes, state_bytes))
    throw fail("the file is damaged (its checksum does not match its contents)");

  CheckpointHeader header;
  try {
    ArchiveReader head(head_bytes.data(), head_bytes.size());
    unarchive(head, header);
  } catch (const ArchiveError& e) {
    throw fail(fmt::format("its header cannot be read ({})", e.what()));
  }
  if (header.scene != identity.scene || header.scene_fingerprint != identity.scene_fingerprint)
    throw fail(fmt::format("the checkpoint was written for scene '{}' (fingerprint {}), not for this scene '{}' "
                           "(fingerprint {}); a restart needs the same scene, with only settings.duration, output and "
                           "threads free to change",
                           header.scene, header.scene_fingerprint, identity.scene, identity.scene_fingerprint));
  if (header.engine != identity.engine)
    throw fail(fmt::format("the checkpoint holds a '{}' state and this scene runs '{}'", header.engine, identity.engine));
  if (header.layout != identity.layout)
    throw fail(fmt::format("the checkpoint's state does not fit this scene: {} (was a mesh file changed?)",
                           layout_difference(header.layout, identity.layout)));

  ArchiveWriter backup;  // the engine as it was, if the state does not load
  engine.save_state(backup);
  try {
    ArchiveReader state(state_bytes.data(), state_bytes.size());
    engine.load_state(state);
    if (state.remaining() != 0) throw ArchiveError(fmt::format("{} bytes are left over", state.remaining()));
  } catch (const ArchiveError& e) {
    ArchiveReader restore(backup.buffer().data(), backup.buffer().size());
    engine.load_state(restore);
    throw fail(fmt::format("its state does not fit this scene's engine ({})", e.what()));
  }
  return header;
}

}  // namespace moreau
