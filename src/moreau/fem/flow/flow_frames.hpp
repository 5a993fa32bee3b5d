#pragma once
// Frames of a flow run: one .vtu per output step (frames/<fluid>_<frame>.vtu) with the velocity,
// the pressure and the vorticity at the nodes (2D in the xy plane, the vorticity a scalar there),
// and <scene>.pvd. Immersed solids are written beside the fluid in the same collection
// (frames/<solid>_<frame>.vtu, as the FEM solids: deformed nodes, displacement, velocity,
// cauchy_stress and von_mises).
#include <string>
#include <vector>

#include "moreau/fem/flow/navier_stokes.hpp"
#include "moreau/fem/immersed/immersed_solids.hpp"
#include "moreau/io/pvd_collection.hpp"
#include "moreau/io/vtk_writer.hpp"

namespace moreau {

class FlowFrameWriter {
 public:
  /// Starts a series in out_dir, or continues `resume` (a restarted run).
  FlowFrameWriter(const NavierStokesModel& model, std::string fluid_name, std::string out_dir, std::string scene_name,
                  FrameSeries resume = {}, const ImmersedSolids* solids = nullptr)
      : model_(model), solids_(solids), fluid_name_(std::move(fluid_name)), out_dir_(std::move(out_dir)),
        scene_name_(safe_file_name(scene_name)), frames_(resume.frames), pvd_(out_dir_ + "/" + scene_name_ + ".pvd", resume) {}

  /// The fluid at x and, with immersed solids, their state at the same time.
  void write(const VectorX& x, Real time, const ImmersedSolidState* solids = nullptr);
  FrameSeries series() const { return {frames_, pvd_.bytes()}; }

 private:
  const NavierStokesModel& model_;
  const ImmersedSolids* solids_;
  std::string fluid_name_, out_dir_, scene_name_;
  int frames_ = 0;
  PvdCollection pvd_;
};

}  // namespace moreau
