#include "moreau/fem/flow/flow_frames.hpp"

#include <fmt/format.h>

#include "moreau/fem/flow/flow_problem.hpp"
#include "moreau/fem/scene/fem_output.hpp"
#include "moreau/io/frame_writer.hpp"

namespace moreau {

void FlowFrameWriter::write(const VectorX& x, Real time, const ImmersedSolidState* solids) {
  const Index n = model_.mesh.node_count();
  std::vector<Vec3> velocity(n, Vec3::Zero());
  std::vector<Real> pressure(n);
  for (Index a = 0; a < n; ++a) {
    for (int k = 0; k < model_.dim(); ++k) velocity[a][k] = x[model_.dof(a, k)];
    pressure[a] = x[model_.dof(a, model_.dim())];
  }
  std::vector<VtkPointArray> vectors{{"velocity", velocity}};
  std::vector<VtkScalarArray> scalars{{"pressure", pressure}};
  const std::vector<Vec3> curl = nodal_vorticity(model_, x);
  if (model_.dim() == 2) {
    std::vector<Real> w(n);
    for (Index a = 0; a < n; ++a) w[a] = curl[a].z();
    scalars.push_back({"vorticity", w});
  } else {
    vectors.push_back({"vorticity", curl});
  }
  const std::string file = fmt::format("frames/{}_{:06d}.vtu", safe_file_name(fluid_name_), frames_);
  write_vtu(out_dir_ + "/" + file, model_.mesh.nodes, model_.mesh.cells, model_.mesh.nodes_per_cell(),
            vtk_cell(model_.mesh.element), vectors, {}, scalars);
  std::vector<PvdEntry> entries{{time, 0, file}};
  if (solids_ && solids) {
    const FemModel& model = solids_->model;
    for (size_t i = 0; i < model.solids.size(); ++i) {
      const std::string solid_file =
          write_solid_frame(model, model.solids[i], solids->displacement, solids->velocity, out_dir_, frames_);
      entries.push_back({time, static_cast<int>(i) + 1, solid_file});
    }
  }
  ++frames_;
  pvd_.add_frame(entries);
}

}  // namespace moreau
