#include "moreau/io/frame_writer.hpp"

#include <fmt/format.h>

#include <filesystem>

#include <algorithm>
#include <fstream>

#include "moreau/collision/collider_surface.hpp"
#include "moreau/errors.hpp"
#include "moreau/io/continuum_frame.hpp"
#include "moreau/io/rod_frame.hpp"
#include "moreau/collision/shape_surface.hpp"

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

FrameWriter::FrameWriter(const Model& model, std::string out_dir, std::string scene_name, FrameSeries resume)
    : model_(model), out_dir_(std::move(out_dir)), scene_name_(safe_file_name(scene_name)), frames_(resume.frames),
      pvd_(out_dir_ + "/" + scene_name_ + ".pvd", resume) {
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
    const ObjectInfo& obj = model_.objects[o];
    const bool particles_only = obj.kind == ObjectKind::fluid || obj.kind == ObjectKind::rod ||
                                obj.kind == ObjectKind::granular || obj.kind == ObjectKind::shape_matched ||
                                obj.kind == ObjectKind::continuum;  // .vtp files
    const std::string file = fmt::format("frames/{}_{:06d}.{}", safe_file_name(obj.name), frames_, particles_only ? "vtp" : "vtu");
    const std::string path = out_dir_ + "/" + file;
    if (obj.kind == ObjectKind::fluid) {
      // Live particles of this fluid: position, velocity, density, pressure, stable id.
      const FluidState& f = state.fluid;
      std::vector<Vec3> x, v;
      std::vector<Real> density, pressure, id;
      for (Index i = 0; i < f.count; ++i) {
        if (f.phase[i] != obj.fluid_phase) continue;
        x.push_back(f.position[i]);
        v.push_back(f.velocity[i]);
        density.push_back(f.density[i]);
        pressure.push_back(f.pressure[i]);
        id.push_back(f.id[i]);
      }
      write_vtp(path, x, {{"velocity", v}},
                {{"density", density}, {"pressure", pressure}, {"id", id},
                 {"radius", std::vector<Real>(x.size(), model_.fluid.particle_radius)}});
    } else if (obj.kind == ObjectKind::granular || obj.kind == ObjectKind::shape_matched) {
      // Grains or shape-matched particles: position, velocity, displacement and radius
      // (ParaView: "Point Gaussian" by radius); grains also their angular velocity and, with
      // settings.sleep, whether each sleeps (1) or not (0). The grains an emitter has not
      // released (the object's last, grain_emitter.hpp) are left out.
      const Index b = obj.particle_begin;
      Index n = obj.particle_count();
      while (n > 0 && !state.live(b + n - 1)) --n;
      std::vector<Vec3> x(state.position.begin() + b, state.position.begin() + b + n);
      std::vector<Vec3> v(state.velocity.begin() + b, state.velocity.begin() + b + n), u(n);
      for (Index i = 0; i < n; ++i) u[i] = x[i] - model_.particle_rest_position[b + i];
      std::vector<VtkScalarArray> scalars{
          {"radius", std::vector<Real>(model_.particle_radius.begin() + b, model_.particle_radius.begin() + b + n)}};
      if (model_.settings.sleep.enabled && obj.kind == ObjectKind::granular) {
        std::vector<Real> asleep(n);
        for (Index i = 0; i < n; ++i) asleep[i] = state.sleep.asleep(b + i) ? 1 : 0;
        scalars.push_back({"asleep", std::move(asleep)});
      }
      std::vector<VtkPointArray> vectors{{"velocity", v}, {"displacement", u}};
      if (obj.kind == ObjectKind::granular)
        vectors.push_back({"angular_velocity", std::vector<Vec3>(state.angular_velocity.begin() + b,
                                                                  state.angular_velocity.begin() + b + n)});
      write_vtp(path, x, vectors, scalars);
    } else if (obj.kind == ObjectKind::continuum) {
      write_continuum_frame(path, model_, obj, state);
    } else if (obj.kind == ObjectKind::rod) {
      write_rod_frame(path, model_, model_.rods[obj.rod], state);
    } else if (obj.kind == ObjectKind::rigid_body) {
      // The body's surface in the world, with the velocity of each surface point.
      const Index b = obj.body;
      const TriangleMesh m = shape_surface(model_.rigid.body_shape[b]);
      const Quat& q = state.rigid.orientation[b];
      const Vec3& x = state.rigid.position[b];
      std::vector<Vec3> points(m.vertices.size()), velocity(m.vertices.size());
      for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 r = q * m.vertices[i];
        points[i] = x + r;
        velocity[i] = state.rigid.velocity[b] + state.rigid.angular_velocity[b].cross(r);
      }
      std::vector<Index> conn;
      for (const auto& t : m.triangles) conn.insert(conn.end(), t.begin(), t.end());
      write_vtu(path, points, conn, 3, VtkCell::triangle, {{"velocity", velocity}});
    } else if (obj.kind == ObjectKind::collider) {
      const Collider& collider = model_.colliders[obj.collider];
      // A removed collider (`until`) is written without a surface, so the series keeps its files.
      const TriangleMesh m = collider.present_at(state.time) ? collider_surface(collider, state.time, plane_half_size_)
                                                             : TriangleMesh{};
      std::vector<Index> conn;
      for (const auto& t : m.triangles) conn.insert(conn.end(), t.begin(), t.end());
      const Vec3 v = model_.colliders[obj.collider].velocity;
      write_vtu(path, m.vertices, conn, 3, VtkCell::triangle, {{"velocity", std::vector<Vec3>(m.vertices.size(), v)}});
    } else {
      const Index b = obj.particle_begin, n = obj.particle_count();
      std::vector<Vec3> x(state.position.begin() + b, state.position.begin() + b + n);
      std::vector<Vec3> v(state.velocity.begin() + b, state.velocity.begin() + b + n);
      std::vector<Vec3> u(n);
      for (Index i = 0; i < n; ++i) u[i] = x[i] - model_.particle_rest_position[b + i];
      std::vector<Index> conn;
      if (obj.kind == ObjectKind::soft_body) {
        for (const auto& t : obj.tets)
          for (Index p : t) conn.push_back(p - b);
        write_vtu(path, x, conn, 4, VtkCell::tetra, {{"velocity", v}, {"displacement", u}});
      } else {
        for (const auto& t : obj.surface)
          for (Index p : t) conn.push_back(p - b);
        write_vtu(path, x, conn, 3, VtkCell::triangle, {{"velocity", v}, {"displacement", u}});
      }
    }
    entries.push_back({state.time, static_cast<int>(o), file});
  }
  pvd_.add_frame(entries);
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
