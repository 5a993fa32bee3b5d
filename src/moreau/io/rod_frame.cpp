#include "moreau/io/rod_frame.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/constraints/joints/joint_frames.hpp"
#include "moreau/rods/rod_geometry.hpp"

namespace moreau {

ObjectFrame rod_frame(const Model& model, const RodModel& rod, const State& state) {
  const RigidBodyState& bodies = state.rigid;
  const Index n = rod.points();
  std::vector<Vec3> points(n), velocity(n), displacement(n);
  std::vector<Real> curvature(n, 0), twist(n, 0), stretch(n, 0);
  for (Index k = 0; k < n; ++k) {
    points[k] = rod_point(rod, bodies, k);
    velocity[k] = rod_point_velocity(rod, bodies, k);
    displacement[k] = points[k] - rod.rest_points[k];
  }
  std::vector<Vec3> tangent(rod.segments), normal(rod.segments), binormal(rod.segments);
  for (Index s = 0; s < rod.segments; ++s) {
    const Quat& q = bodies.orientation[rod.first_body + s];
    normal[s] = q * Vec3::UnitX();
    tangent[s] = q * Vec3::UnitY();
    binormal[s] = q * Vec3::UnitZ();
  }
  for (Index k = 1; k < rod.segments; ++k) {
    const Joint& j = model.joints[rod.first_joint + k - 1];
    const Real length = (rod.segment_length[k - 1] + rod.segment_length[k]) / 2;
    const Vec3& ta = tangent[k - 1];
    const Vec3& tb = tangent[k];
    curvature[k] = std::atan2(ta.cross(tb).norm(), ta.dot(tb)) / length;
    const JointEndPose a = end_pose(state, j.ends[0]), b = end_pose(state, j.ends[1]);
    twist[k] = junction_twist(j, state) / length;
    stretch[k] = a.axis(0).dot(b.anchor() - a.anchor()) / length;
  }
  return {.cells = ObjectFrame::Cells::polyline,
          .points = std::move(points),
          .point_vectors = {{"velocity", std::move(velocity)}, {"displacement", std::move(displacement)}},
          .point_scalars = {{"curvature", std::move(curvature)}, {"twist", std::move(twist)}, {"stretch", std::move(stretch)}},
          .cell_vectors = {{"tangent", std::move(tangent)}, {"normal", std::move(normal)}, {"binormal", std::move(binormal)}}};
}

}  // namespace moreau
