#include "moreau/geometry/gmsh_reader.hpp"

#include <fmt/format.h>

#include <unordered_map>

#include "moreau/geometry/line_reader.hpp"

namespace moreau {

int gmsh_node_count(GmshElementType type) {
  switch (type) {
    case GmshElementType::line2: return 2;
    case GmshElementType::tri3: return 3;
    case GmshElementType::quad4: return 4;
    case GmshElementType::tet4: return 4;
    case GmshElementType::hex8: return 8;
    case GmshElementType::point: return 1;
    case GmshElementType::other: return 0;
  }
  return 0;
}

namespace {

GmshElementType element_type(int number) {
  switch (number) {
    case 1: return GmshElementType::line2;
    case 2: return GmshElementType::tri3;
    case 3: return GmshElementType::quad4;
    case 4: return GmshElementType::tet4;
    case 5: return GmshElementType::hex8;
    case 15: return GmshElementType::point;
    default: return GmshElementType::other;
  }
}

// $Entities: points "tag x y z nphys phys...", curves/surfaces/volumes
// "tag minx miny minz maxx maxy maxz nphys phys... nbound bound..." (MSH 4.1).
void read_entities(LineReader& r, GmshFile& file) {
  std::istringstream line;
  long counts[4] = {0, 0, 0, 0};
  if (!r.next(line) || !(line >> counts[0] >> counts[1] >> counts[2] >> counts[3])) r.fail("malformed $Entities header");
  for (int dim = 0; dim < 4; ++dim)
    for (long e = 0; e < counts[dim]; ++e) {
      if (!r.next(line)) r.fail("unexpected end of file in $Entities");
      int tag = 0;
      double box[6];
      const int coordinates = dim == 0 ? 3 : 6;
      line >> tag;
      for (int k = 0; k < coordinates; ++k) line >> box[k];
      long physical_count = 0;
      if (!(line >> physical_count) || physical_count < 0) r.fail("malformed entity (its number of physical tags)");
      // Read tag by tag rather than sizing for the count: a corrupt count (10^18) then fails at the
      // first missing tag instead of allocating (found by fuzzing).
      std::vector<int> physicals;
      for (long k = 0; k < physical_count; ++k) {
        int p = 0;
        if (!(line >> p)) r.fail("malformed entity physical tags");
        physicals.push_back(p);
      }
      file.entity_physicals[{dim, tag}] = physicals;
    }
}

}  // namespace

GmshFile read_gmsh_file(const std::string& path) {
  LineReader r{open_or_throw(path), path};
  std::istringstream line;
  std::string section;
  bool version_ok = false;
  std::unordered_map<long, Index> node_index;
  GmshFile file;
  struct RawBlock {
    GmshElementBlock block;
    std::vector<long> tags;
    int line;
  };
  std::vector<RawBlock> raw;
  while (r.next(line)) {
    line >> section;
    if (section == "$MeshFormat") {
      double version = 0;
      int file_type = -1;
      if (!r.next(line) || !(line >> version >> file_type)) r.fail("malformed $MeshFormat section");
      if (version < 4.0 || version >= 5.0) r.fail(fmt::format("MSH version {} is not supported; allowed: 4.1 ASCII", version));
      if (file_type != 0) r.fail("binary MSH files are not supported; save as ASCII (Gmsh: -format msh4 -bin 0)");
      version_ok = true;
    } else if (section == "$PhysicalNames") {
      long count = 0;
      if (!r.next(line) || !(line >> count)) r.fail("malformed $PhysicalNames header");
      for (long i = 0; i < count; ++i) {
        int dim = 0, tag = 0;
        std::string name;
        if (!r.next(line) || !(line >> dim >> tag)) r.fail("malformed physical name");
        std::getline(line, name);
        const auto first = name.find('"'), last = name.rfind('"');
        if (first == std::string::npos || last == first) r.fail("a physical name must be quoted");
        file.physical_names[{dim, tag}] = name.substr(first + 1, last - first - 1);
      }
    } else if (section == "$Entities") {
      read_entities(r, file);
    } else if (section == "$Nodes") {
      if (!version_ok) r.fail("$Nodes before $MeshFormat");
      long blocks = 0, count = 0;
      if (!r.next(line) || !(line >> blocks >> count)) r.fail("malformed $Nodes header");
      for (long b = 0; b < blocks; ++b) {
        int dim = 0, entity = 0, parametric = 0;
        long in_block = 0;
        if (!r.next(line) || !(line >> dim >> entity >> parametric >> in_block)) r.fail("malformed node block header");
        if (parametric != 0) r.fail("parametric nodes are not supported");
        if (in_block < 0) r.fail("malformed node block header (a negative node count)");
        // Tag by tag, not sized for the count: a corrupt count fails at the first missing line.
        std::vector<long> tags;
        for (long k = 0; k < in_block; ++k) {
          long tag = 0;
          if (!r.next(line) || !(line >> tag)) r.fail("malformed node tag");
          tags.push_back(tag);
        }
        for (long tag : tags) {
          double x, y, z;
          if (!r.next(line) || !(line >> x >> y >> z)) r.fail("malformed node coordinates");
          node_index[tag] = static_cast<Index>(file.nodes.size());
          file.nodes.emplace_back(x, y, z);
        }
      }
    } else if (section == "$Elements") {
      long blocks = 0, count = 0;
      if (!r.next(line) || !(line >> blocks >> count)) r.fail("malformed $Elements header");
      for (long b = 0; b < blocks; ++b) {
        int dim = 0, entity = 0, type = 0;
        long in_block = 0;
        if (!r.next(line) || !(line >> dim >> entity >> type >> in_block)) r.fail("malformed element block header");
        RawBlock block{{dim, entity, element_type(type), {}}, {}, r.line_number};
        const int per = gmsh_node_count(block.block.type);
        for (long e = 0; e < in_block; ++e) {
          if (!r.next(line)) r.fail("unexpected end of file in $Elements");
          if (per == 0) continue;
          long tag, node;
          if (!(line >> tag)) r.fail("malformed element");
          for (int k = 0; k < per; ++k) {
            if (!(line >> node)) r.fail(fmt::format("malformed element: expected {} nodes", per));
            block.tags.push_back(node);
          }
        }
        if (per > 0) raw.push_back(std::move(block));
      }
    }
  }
  if (!version_ok) throw InputError(fmt::format("{}: not a Gmsh MSH file (no $MeshFormat section)", path));
  for (RawBlock& b : raw) {
    for (long tag : b.tags) {
      const auto it = node_index.find(tag);
      if (it == node_index.end())
        throw InputError(fmt::format("{}: an element of the block at line {} refers to unknown node {}", path, b.line, tag));
      b.block.nodes.push_back(it->second);
    }
    file.blocks.push_back(std::move(b.block));
  }
  return file;
}

}  // namespace moreau
