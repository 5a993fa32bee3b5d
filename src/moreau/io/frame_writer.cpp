#include "moreau/io/frame_writer.hpp"

#include <fmt/format.h>

#include <filesystem>

#include <algorithm>
#include <fstream>

#include "moreau/errors.hpp"
#include "moreau/io/object_frame.hpp"

namespace moreau {

void FrameWriter::write_rigid_poses(const State& state) {
  const bool any = std::any_of(model_.objects.begin(), model_.objects.end(),
                               [](const ObjectInfo& o) { return o.kind == ObjectKind::rigid_body; });
  if (!any) return;
  std::ofstream out(out_dir_ + "/rigid_poses.csv", frames_ == 0 ? std::ios::trunc : std::ios::app);
  if (frames_ == 0) out << "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  out.precision(17);
  for (const ObjectInfo& o : model_.objects) {
    if (o.kind != ObjectKind::rigid_body) continue;
    // The pose of the shape's own frame (the scene's position and orientation).
    const Index b = o.body;
    const Quat q = (state.rigid.orientation[b] * model_.rigid.body_frame_in_shape[b].conjugate()).normalized();
    const Vec3 x = state.rigid.position[b] - q * model_.rigid.body_center_in_shape[b];
    const Vec3& v = state.rigid.velocity[b];
    const Vec3& w = state.rigid.angular_velocity[b];
    out << state.time << ',' << o.name << ',' << x.x() << ',' << x.y() << ',' << x.z() << ',' << q.w() << ',' << q.x()
        << ',' << q.y() << ',' << q.z() << ',' << v.x() << ',' << v.y() << ',' << v.z() << ',' << w.x() << ','
        << w.y() << ',' << w.z() << '\n';
  }
}

FrameWriter::FrameWriter(const Model& model, std::string out_dir, std::string scene_name, FrameFormats formats,
                         FrameSeries resume)
    : model_(model), out_dir_(std::move(out_dir)), scene_name_(safe_file_name(scene_name)), formats_(formats),
      frames_(resume.frames) {
  if (formats_.vtk) pvd_.emplace(out_dir_ + "/" + scene_name_ + ".pvd", resume);
  // Draw planes large enough to hold the scene's particles.
  Vec3 lo = Vec3::Constant(-1), hi = Vec3::Constant(1);
  for (const auto& x : model.particle_rest_position) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  for (const auto& x : model.fluid.initial_position) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  for (const ObjectInfo& o : model.objects)
    if (o.has_bodies())
      for (Index b = o.body; b < o.body + o.body_count; ++b) {
        lo = lo.cwiseMin(model.rigid.initial_position[b]);
        hi = hi.cwiseMax(model.rigid.initial_position[b]);
      }
  for (const auto& e : model.fluid.emitters) {
    lo = lo.cwiseMin(e.center);
    hi = hi.cwiseMax(e.center);
  }
  plane_half_size_ = 0.75 * (hi - lo).maxCoeff();
}

void FrameWriter::write(const State& state) {
  std::vector<PvdEntry> entries;
  for (size_t o = 0; o < model_.objects.size(); ++o) {
    const ObjectInfo& object = model_.objects[o];
    const ObjectFrame frame = object_frame(model_, object, state, plane_half_size_);
    const std::string stem = fmt::format("frames/{}_{:06d}", safe_file_name(object.name), frames_);
    if (formats_.vtk) {
      const std::string file = stem + "." + vtk_extension(frame);
      write_vtk_frame(out_dir_ + "/" + file, frame);
      entries.push_back({state.time, static_cast<int>(o), file});
    }
    if (formats_.obj && has_surface(frame)) write_obj_frame(out_dir_ + "/" + stem + ".obj", object.name, frame);
    if (formats_.ply && is_point_set(frame)) write_ply_frame(out_dir_ + "/" + stem + ".ply", object.name, frame);
  }
  if (pvd_) pvd_->add_frame(entries);
  write_rigid_poses(state);
  ++frames_;
}

void prepare_output_directory(const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path dir(out_dir);
  fs::create_directories(dir);
  fs::remove_all(dir / "frames");
  fs::create_directories(dir / "frames");
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".pvd") fs::remove(entry.path());
  fs::remove(dir / "checkpoint.bin");
}

void resume_output_directory(const std::string& out_dir, const FrameSeries& frames,
                             const std::vector<std::pair<std::string, std::uint64_t>>& appended_files) {
  namespace fs = std::filesystem;
  const fs::path dir(out_dir);
  try {
    for (const auto& [name, size] : appended_files) {
      if (!fs::exists(dir / name) || fs::file_size(dir / name) < size)
        throw InputError(fmt::format("--out {}: {} is shorter than when the checkpoint was written; restart into an empty "
                                     "directory with --out",
                                     out_dir, name));
      fs::resize_file(dir / name, size);
    }
    // Frames are frames/<object>_<NNNNNN>.<ext>: those numbered from frames.frames on are later
    // than the checkpoint; anything else there (a partial .part file) goes too.
    fs::create_directories(dir / "frames");
    std::vector<fs::path> stale;
    for (const auto& entry : fs::directory_iterator(dir / "frames")) {
      const std::string stem = entry.path().stem().string();
      const std::string number = stem.substr(stem.rfind('_') + 1);
      const bool numbered = !number.empty() && number.find_first_not_of("0123456789") == std::string::npos;
      if (!numbered || std::stol(number) >= frames.frames) stale.push_back(entry.path());
    }
    for (const fs::path& p : stale) fs::remove(p);
  } catch (const fs::filesystem_error& e) {
    throw InputError(fmt::format("--out {}: cannot continue the output directory ({})", out_dir, e.code().message()));
  }
}

void writable_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(fmt::format("--out {}: exists and is not a directory; give a directory (it is created if missing)", dir));
  try {
    fs::create_directories(dir);
  } catch (const fs::filesystem_error& e) {
    throw InputError(fmt::format("--out {}: cannot prepare the output directory ({}); choose a writable directory", dir,
                                 e.code().message()));
  }
  // A directory that can be created but not written (a read-only mount, /proc, /sys).
  const fs::path probe = fs::path(dir) / ".moreau-write-test";
  if (!std::ofstream(probe) || !fs::remove(probe, ec))
    throw InputError(fmt::format("--out {}: the directory is not writable; choose a writable directory", dir));
}

std::string output_directory_path(const std::string& requested, const std::string& scene_name) {
  return requested.empty() ? "out/" + safe_file_name(scene_name) : requested;
}

std::string run_output_directory(const std::string& requested, const std::string& scene_name) {
  const std::string dir = output_directory_path(requested, scene_name);
  writable_directory(dir);
  try {
    prepare_output_directory(dir);
  } catch (const std::filesystem::filesystem_error& e) {
    throw InputError(fmt::format("--out {}: cannot prepare the output directory ({}); choose a writable directory", dir,
                                 e.code().message()));
  }
  return dir;
}

}  // namespace moreau
