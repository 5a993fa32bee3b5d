#pragma once
// Frames of a flow run: one .vtu per output step (frames/<fluid>_<frame>.vtu) with the velocity,
// the pressure and the vorticity at the nodes (2D in the xy plane, the vorticity a scalar there),
// and <scene>.pvd.
#include <string>
#include <vector>

#include "moreau/fem/flow/navier_stokes.hpp"
#include "moreau/io/pvd_collection.hpp"
#include "moreau/io/vtk_writer.hpp"

namespace moreau {

class FlowFrameWriter {
 public:
  /// Starts a series in out_dir, or continues `resume` (a restarted run).
  FlowFrameWriter(const NavierStokesModel& model, std::string fluid_name, std::string out_dir, std::string scene_name,
                  FrameSeries resume = {})
      : model_(model), fluid_name_(std::move(fluid_name)), out_dir_(std::move(out_dir)), scene_name_(safe_file_name(scene_name)),
        frames_(resume.frames), pvd_(out_dir_ + "/" + scene_name_ + ".pvd", resume) {}

  void write(const VectorX& x, Real time);
  FrameSeries series() const { return {frames_, pvd_.bytes()}; }

 private:
  const NavierStokesModel& model_;
  std::string fluid_name_, out_dir_, scene_name_;
  int frames_ = 0;
  PvdCollection pvd_;
};

}  // namespace moreau
