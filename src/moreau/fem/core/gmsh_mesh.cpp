// FEM meshes from Gmsh files: cells, and boundaries from physical groups.
#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "moreau/errors.hpp"
#include "moreau/fem/core/fem_mesh.hpp"
#include "moreau/geometry/gmsh_reader.hpp"

namespace moreau {

namespace {

ElementType fem_type(GmshElementType type) {
  switch (type) {
    case GmshElementType::line2: return ElementType::line2;
    case GmshElementType::tri3: return ElementType::tri3;
    case GmshElementType::quad4: return ElementType::quad4;
    case GmshElementType::tet4: return ElementType::tet4;
    case GmshElementType::hex8: return ElementType::hex8;
    default: break;
  }
  return ElementType::line2;
}

}  // namespace

FemMesh read_gmsh_fem_mesh(const std::string& path) {
  const GmshFile file = read_gmsh_file(path);
  int dim = 0;
  for (const GmshElementBlock& b : file.blocks)
    if (b.type != GmshElementType::point) dim = std::max(dim, b.dim);
  if (dim < 2) throw InputError(fmt::format("{}: no 2D or 3D elements (tri3, quad4, tet4, hex8) in the file", path));
  FemMesh mesh;
  mesh.dim = dim;
  bool typed = false;
  std::vector<Index> renumber(file.nodes.size(), -1);
  auto local = [&](Index n) {
    if (renumber[n] < 0) {
      renumber[n] = mesh.node_count();
      mesh.nodes.push_back(file.nodes[n]);
    }
    return renumber[n];
  };
  for (const GmshElementBlock& b : file.blocks) {
    if (b.dim != dim) continue;
    const ElementType type = fem_type(b.type);
    if (element_dimension(type) != dim)
      throw InputError(fmt::format("{}: element type {} is not supported in {}D; allowed: {}", path, static_cast<int>(b.type),
                                   dim, dim == 2 ? "tri3 (2), quad4 (3)" : "tet4 (4), hex8 (5)"));
    if (typed && type != mesh.element)
      throw InputError(fmt::format("{}: mixes {} and {} cells; a mesh has one cell type", path, element_name(mesh.element),
                                   element_name(type)));
    mesh.element = type;
    typed = true;
    for (Index n : b.nodes) mesh.cells.push_back(local(n));
  }
  if (dim == 2)
    for (const Vec3& x : mesh.nodes)
      if (x.z() != 0) throw InputError(fmt::format("{}: a 2D mesh must lie in the plane z = 0", path));
  // Boundaries: physical groups of dimension dim - 1, through the entities that carry them.
  std::map<int, FemBoundary> groups;
  for (const GmshElementBlock& b : file.blocks) {
    if (b.dim != dim - 1) continue;
    const auto physicals = file.entity_physicals.find({b.dim, b.entity});
    if (physicals == file.entity_physicals.end() || physicals->second.empty()) continue;
    if (fem_type(b.type) != facet_type(mesh.element))
      throw InputError(fmt::format("{}: a boundary group of {} cells must consist of {} facets", path,
                                   element_name(mesh.element), element_name(facet_type(mesh.element))));
    for (int tag : physicals->second) {
      FemBoundary& group = groups[tag];
      const auto name = file.physical_names.find({b.dim, tag});
      group.name = name != file.physical_names.end() ? name->second : fmt::format("physical_{}", tag);
      for (Index n : b.nodes) {
        if (renumber[n] < 0)
          throw InputError(fmt::format("{}: physical group '{}' has a node that no cell uses", path, group.name));
        group.facets.push_back(renumber[n]);
      }
    }
  }
  for (auto& [tag, group] : groups) mesh.boundaries.push_back(std::move(group));
  if (mesh.cells.empty()) throw InputError(fmt::format("{}: no cells", path));
  return mesh;
}

}  // namespace moreau
