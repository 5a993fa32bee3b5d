#pragma once
// Frames of a FEM run: one .vtu per solid and output step with the deformed nodes, point arrays
// displacement and velocity, and cell arrays cauchy_stress (the Cauchy stress
// sigma = J^-1 F S F^T averaged over the cell's quadrature points, a symmetric tensor) and
// von_mises (sqrt(3/2 s:s), s the deviator of that average). 2D solids are written in the xy plane.
// Rigid bodies are written as their mesh carried by the directors, x = phi + sum_i ((X - c) . a_i)
// d_i, with the velocity of each node.
#include <string>
#include <vector>

#include "moreau/fem/scene/fem_problem.hpp"
#include "moreau/io/pvd_collection.hpp"
#include "moreau/io/vtk_writer.hpp"

namespace moreau {

/// The VTK cell type of an element type.
VtkCell vtk_cell(ElementType type);

/// Per cell of a solid: the 6 Cauchy stress components (xx, yy, zz, xy, yz, xz) and von Mises.
void cell_stresses(const FemModel& model, const FemSolid& solid, const VectorX& u, std::vector<Real>& cauchy,
                   std::vector<Real>& von_mises);

/// Writes a solid's frame (frames/<solid>_<frame>.vtu in out_dir, returned): its deformed mesh
/// with point arrays displacement and velocity and cell arrays cauchy_stress and von_mises, from
/// the displacements u and velocities v over the model's dofs.
std::string write_solid_frame(const FemModel& model, const FemSolid& solid, const VectorX& u, const VectorX& v,
                              const std::string& out_dir, int frame);

class FemFrameWriter {
 public:
  /// Starts a series in out_dir, or continues `resume` (a restarted run).
  FemFrameWriter(const FemProblem& problem, std::string out_dir, std::string scene_name, FrameSeries resume = {})
      : problem_(problem), model_(problem.model), out_dir_(std::move(out_dir)), scene_name_(safe_file_name(scene_name)),
        frames_(resume.frames), pvd_(out_dir_ + "/" + scene_name_ + ".pvd", resume) {}
  void write(const FemRunState& state);
  FrameSeries series() const { return {frames_, pvd_.bytes()}; }

 private:
  const FemProblem& problem_;
  const FemModel& model_;
  std::string out_dir_, scene_name_;
  int frames_ = 0;
  PvdCollection pvd_;
};

}  // namespace moreau
