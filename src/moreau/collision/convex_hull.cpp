// Convex hulls through qhull (Barber, Dobkin, Huhdanpaa 1996, the Quickhull algorithm), reentrant C
// API. qhull merges coplanar facets by default in 3D, so a box given as 8 corners comes back as 6
// quadrilaterals, which the face-clipping narrow phase needs.
extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "moreau/collision/shape.hpp"

namespace moreau {

ConvexPolyhedron convex_hull(const std::vector<Vec3>& points) {
  if (points.size() < 4) throw std::invalid_argument("a convex hull needs at least 4 points");
  std::vector<coordT> coords;
  coords.reserve(points.size() * 3);
  for (const Vec3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});

  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, stderr);
  char options[] = "qhull Qs";
  FILE* silent = fopen("/dev/null", "w");
  const int status = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, options, nullptr,
                                  silent ? silent : stderr);
  ConvexPolyhedron hull;
  if (status == 0) {
    // Keep only the points qhull used, renumbered.
    std::vector<Index> renumber(points.size(), -1);
    facetT* facet;
    vertexT *vertex, **vertexp;
    FORALLfacets {
      const Vec3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
      std::vector<Index> face;
      Vec3 centroid = Vec3::Zero();
      FOREACHvertex_(facet->vertices) {
        const int id = qh_pointid(qh, vertex->point);
        if (renumber[id] < 0) {
          renumber[id] = static_cast<Index>(hull.vertices.size());
          hull.vertices.push_back(points[id]);
        }
        face.push_back(renumber[id]);
        centroid += points[id];
      }
      centroid /= Real(face.size());
      // qhull lists a merged facet's vertices unordered: sort them counter-clockwise about the
      // outward normal.
      const Vec3 u = (hull.vertices[face[0]] - centroid).normalized();
      const Vec3 v = normal.cross(u);
      std::sort(face.begin(), face.end(), [&](Index a, Index b) {
        const Vec3 da = hull.vertices[a] - centroid, db = hull.vertices[b] - centroid;
        return std::atan2(da.dot(v), da.dot(u)) < std::atan2(db.dot(v), db.dot(u));
      });
      hull.faces.push_back(std::move(face));
    }
  }
  int curlong = 0, totlong = 0;
  qh_freeqhull(qh, !qh_ALL);
  qh_memfreeshort(qh, &curlong, &totlong);
  if (silent) fclose(silent);
  if (status != 0 || hull.faces.size() < 4)
    throw std::invalid_argument("the points are flat or degenerate: their convex hull has no volume");
  hull.finish_topology();
  return hull;
}

}  // namespace moreau
