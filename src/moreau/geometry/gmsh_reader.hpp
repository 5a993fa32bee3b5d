#pragma once
// Gmsh MSH 4.1 ASCII files (https://gmsh.info/doc/texinfo/gmsh.html, "MSH file format"): nodes,
// element blocks per geometric entity, physical names, and the entities' physical tags, so that
// physical groups can name boundaries and regions.
#include <map>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// The element types moreau reads (Gmsh type numbers).
enum class GmshElementType { line2 = 1, tri3 = 2, quad4 = 3, tet4 = 4, hex8 = 5, point = 15, other = 0 };

/// Node count of a Gmsh element type, 0 for types moreau does not read.
int gmsh_node_count(GmshElementType type);

struct GmshElementBlock {
  int dim = 0;                 // of the entity
  int entity = 0;              // entity tag
  GmshElementType type = GmshElementType::other;
  std::vector<Index> nodes;    // node indices (into GmshFile::nodes), gmsh_node_count(type) per element
};

struct GmshFile {
  std::vector<Vec3> nodes;
  std::vector<GmshElementBlock> blocks;                           // blocks of unread types are skipped
  std::map<std::pair<int, int>, std::string> physical_names;      // (dim, physical tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> entity_physicals;  // (dim, entity tag) -> physical tags
};

/// Reads a Gmsh MSH 4.1 ASCII file; every problem is an InputError naming the file and line.
GmshFile read_gmsh_file(const std::string& path);

}  // namespace moreau
