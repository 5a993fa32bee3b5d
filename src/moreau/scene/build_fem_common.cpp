// What the solids and the fluid of a FEM scene read alike: meshes (generated, graded, Gmsh .msh
// or .geo), per-component expressions and node selections (docs/fem-scenes.md).
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <set>
#include <unistd.h>

#include "moreau/scene/memory_estimate.hpp"
#include "moreau/errors.hpp"
#include "moreau/fem/distributed/mpi_ranks.hpp"
#include "moreau/fem/petsc/petsc_plugin_loader.hpp"
#include "moreau/scene/fem_scene.hpp"

namespace moreau {

std::string require_petsc(const JsonObject& linear_solver, const std::vector<std::string>& solvers_options,
                          PetscSystemKind kind) {
  petsc_plugin::Backend* backend = nullptr;
  try {
    backend = &petsc_backend();
  } catch (const std::runtime_error& e) {
    linear_solver.fail("type", std::string("\"petsc\" is not available here: ") + e.what());
  }
  // PETSc rejects an unknown solver or preconditioner type, of the inner solvers too, before the
  // run starts rather than at its first solve.
  std::vector<std::vector<std::string>> unread;
  for (const std::string& options : solvers_options) {
    const PetscOptionCheck check = check_petsc_options(*backend, options, kind);
    if (!check.failure.empty())
      linear_solver.fail(linear_solver.has("petsc_options") ? "petsc_options" : "preconditioner",
                         "PETSc does not accept these options: " + check.failure +
                             "; the KSP and PC types PETSc knows are listed in its manual pages (KSPType, PCType)");
    unread.push_back(check.unused);
  }
  // Only the user's own options are named: a preset's option may go unread because the user's
  // replaced what it was for (a preconditioner type, say). PETSc's names ignore case.
  const auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  };
  std::set<std::string> given;
  if (linear_solver.has("petsc_options")) {
    std::istringstream tokens(linear_solver.string("petsc_options"));
    for (std::string token; tokens >> token;) given.insert(lower(token));
  }
  // Named if no solver read it.
  std::string names;
  for (const std::string& name : unread.front()) {
    const bool everywhere = std::all_of(unread.begin(), unread.end(), [&](const std::vector<std::string>& list) {
      return std::find(list.begin(), list.end(), name) != list.end();
    });
    if (everywhere && given.count(lower(name))) names += (names.empty() ? "" : ", ") + name;
  }
  if (names.empty()) return "";
  return fmt::format("{}: PETSc did not read {} when it built the preconditioner on a small test system: "
                     "misspelt, or meant for a solver or preconditioner these options do not create (options of "
                     "multigrid levels that a small system lacks are read only on the scene's own)",
                     linear_solver.path_of("petsc_options"), names);
}

void require_petsc_when_distributed(const JsonObject& top, const JsonObject* settings, bool uses_petsc) {
  if (uses_petsc || mpi_ranks() <= 1) return;
  const std::string message = fmt::format(
      "this run has {} MPI ranks, which share the FEM engine's linear solves through PETSc: set "
      "\"linear_solver\": {{\"type\": \"petsc\"}} in \"settings\", or run on one process (without mpirun)",
      mpi_ranks());
  if (!settings) top.fail("settings", message);
  if (auto linear = settings->optional_object("linear_solver")) linear->fail("type", message);
  settings->fail("linear_solver", message);
}

Vec3 read_point(const JsonObject& j, const std::string& key, int dim) {
  if (dim == 3) return j.vec3(key);
  const Vec2 p = j.vec2(key, Range::any());
  return Vec3(p.x(), p.y(), 0);
}

namespace {

// "remove": [{"min": [...], "max": [...]}, ...]: cells whose centre lies in a box are dropped.
void remove_boxes(const JsonObject& mesh, FemMesh& result, const Vec3& lo, const Vec3& hi) {
  if (!mesh.has("remove")) return;
  std::vector<std::array<Vec3, 2>> boxes;
  for (const JsonObject& box : mesh.object_list("remove")) {
    boxes.push_back({read_point(box, "min", result.dim), read_point(box, "max", result.dim)});
    box.finish();
  }
  remove_cells(result, boxes, lo, hi);
  if (result.cell_count() == 0) mesh.fail("remove", "removes every cell of the mesh");
}

// The position in [0, 1] of node i of n cells whose sizes grow geometrically so that the largest
// is `ratio` times the smallest: toward "min" (small cells at 0), "max" or "both" (small at both
// ends, largest in the middle).
Real graded_position(int i, int n, Real ratio, const std::string& toward) {
  auto one_sided = [ratio](int k, int cells) {  // small cells at 0, growth q = ratio^(1/(cells-1))
    if (cells < 2 || ratio == 1) return static_cast<Real>(k) / cells;
    const Real q = std::pow(ratio, 1.0 / (cells - 1));
    return (std::pow(q, k) - 1) / (std::pow(q, cells) - 1);
  };
  if (toward == "min") return one_sided(i, n);
  if (toward == "max") return 1 - one_sided(n - i, n);
  // both: mirror a one-sided grading of half the cells (n odd: the middle cell is split evenly).
  const int half = n / 2;
  if (n % 2 == 0) return i <= half ? 0.5 * one_sided(i, half) : 1 - 0.5 * one_sided(n - i, half);
  // n odd: grade n + 1 cells symmetrically and merge the two middle ones.
  const int m = (n + 1) / 2;
  if (i < m) return 0.5 * one_sided(i, m);
  return 1 - 0.5 * one_sided(n - i, m);
}

// "grading": one entry per axis, null (uniform) or {"ratio": r >= 1, "toward": "min" | "max" | "both"}:
// the generated grid's node coordinates are moved to the graded positions.
void grade_mesh(const JsonObject& mesh, FemMesh& result, const Vec3& lo, const Vec3& hi, const std::vector<int>& cells) {
  if (!mesh.has("grading")) return;
  const auto& raw = mesh.raw("grading");
  const int dim = result.dim;
  if (!raw.is_array() || static_cast<int>(raw.size()) != dim)
    mesh.fail("grading", fmt::format("expected {} entries, one per axis: null or {{\"ratio\": r, \"toward\": \"min\" | \"max\" | \"both\"}}", dim));
  for (int k = 0; k < dim; ++k) {
    if (raw[k].is_null()) continue;
    const JsonObject axis(raw[k], mesh.path_of("grading") + fmt::format("[{}]", k), mesh.file());
    const Real ratio = axis.number("ratio", Range{1, 1e6, false, false});
    const std::string toward = axis.choice("toward", "min", {"min", "max", "both"});
    axis.finish();
    const Real length = hi[k] - lo[k];
    for (Vec3& X : result.nodes) {
      const int i = static_cast<int>(std::lround((X[k] - lo[k]) / length * cells[k]));
      X[k] = lo[k] + length * graded_position(i, cells[k], ratio, toward);
    }
  }
}

// A .geo file meshed by Gmsh (in dim dimensions) into a temporary MSH 4.1 file; "parameters":
// {"name": number, ...} are passed as -setnumber (the .geo's DefineConstant values).
std::string mesh_geo_file(const JsonObject& mesh, const std::filesystem::path& geo, int dim) {
  std::string numbers;
  if (mesh.has("parameters")) {
    const auto& raw = mesh.raw("parameters");
    if (!raw.is_object()) mesh.fail("parameters", "expected an object of numbers, e.g. {\"N\": 4}");
    for (const auto& [name, value] : raw.items()) {
      const bool word = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
      if (!word || !value.is_number())
        mesh.fail("parameters", fmt::format("\"{}\": {} is not a parameter name with a number", name, value.dump()));
      numbers += fmt::format(" -setnumber {} {}", name, value.get<Real>());
    }
  }
  if (std::system("command -v gmsh > /dev/null 2>&1") != 0)
    mesh.fail("file", "meshing a .geo file needs Gmsh on the PATH (Debian: apt-get install gmsh); or give a .msh file");
  const std::filesystem::path out = std::filesystem::temp_directory_path() /
                                    fmt::format("moreau-{}-{}.msh", std::hash<std::string>{}(geo.string()), ::getpid());
  const std::filesystem::path log = out.string() + ".log";
  const std::string command = fmt::format("gmsh -{} -format msh41 -v 2{} '{}' -o '{}' > '{}' 2>&1", dim, numbers,
                                          geo.string(), out.string(), log.string());
  const int status = std::system(command.c_str());
  std::string output;
  {
    std::ifstream in(log);
    output.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::filesystem::remove(log);
  if (status != 0 || !std::filesystem::exists(out))
    mesh.fail("file", fmt::format("Gmsh could not mesh '{}':\n{}", geo.string(), output));
  return out.string();
}

}  // namespace

FemMesh read_fem_mesh(const JsonObject& mesh, const std::string& where, MeshUse use) {
  const std::string type = mesh.choice("type", {"box", "rectangle", "msh", "geo"});
  FemMesh result;
  if (type == "msh" || type == "geo") {
    const std::filesystem::path file = mesh.string("file");
    const std::filesystem::path resolved =
        file.is_absolute() ? file : std::filesystem::absolute(mesh.file()).parent_path() / file;
    if (!std::filesystem::exists(resolved)) mesh.fail("file", fmt::format("no file '{}'", resolved.string()));
    if (std::filesystem::is_directory(resolved))
      mesh.fail("file", fmt::format("'{}' is a directory; give the path of a mesh file", resolved.string()));
    if (type == "msh") {
      try {
        result = read_gmsh_fem_mesh(resolved.string());
      } catch (const InputError& e) {
        mesh.fail("file", e.what());
      }
    } else {
      const int dim = mesh.integer("dimension", 2, 2, 3);
      const std::string msh = mesh_geo_file(mesh, resolved, dim);
      try {
        result = read_gmsh_fem_mesh(msh);
      } catch (...) {
        std::filesystem::remove(msh);
        throw;
      }
      std::filesystem::remove(msh);
    }
  } else if (type == "box") {
    const Vec3 lo = mesh.vec3("min"), hi = mesh.vec3("max");
    if (!((hi - lo).array() > 0).all()) mesh.fail("max", "every component of max must exceed min");
    const auto cells = mesh.integers("cells", 3, 1);
    const ElementType element = mesh.choice("element", "hex8", {"hex8", "tet4"}) == "hex8" ? ElementType::hex8 : ElementType::tet4;
    check_memory(SpecPlace(mesh), "cells", double(cells[0]) * cells[1] * cells[2],
                 use == MeshUse::flow ? memory_cost::flow_cell_3d : memory_cost::solid_cell_3d, "cells");
    result = make_box_mesh(lo, hi, {cells[0], cells[1], cells[2]}, element);
    grade_mesh(mesh, result, lo, hi, cells);
    remove_boxes(mesh, result, lo, hi);
  } else {
    const Vec2 lo = mesh.vec2("min", Range::any()), hi = mesh.vec2("max", Range::any());
    if (!((hi - lo).array() > 0).all()) mesh.fail("max", "every component of max must exceed min");
    const auto cells = mesh.integers("cells", 2, 1);
    const ElementType element = mesh.choice("element", "quad4", {"quad4", "tri3"}) == "quad4" ? ElementType::quad4 : ElementType::tri3;
    check_memory(SpecPlace(mesh), "cells", double(cells[0]) * cells[1],
                 use == MeshUse::flow ? memory_cost::flow_cell_2d : memory_cost::solid_cell_2d, "cells");
    result = make_rectangle_mesh(lo, hi, {cells[0], cells[1]}, element);
    const Vec3 lo3(lo.x(), lo.y(), 0), hi3(hi.x(), hi.y(), 0);
    grade_mesh(mesh, result, lo3, hi3, cells);
    remove_boxes(mesh, result, lo3, hi3);
  }
  mesh.finish();
  orient_and_validate_cells(result, where);
  return result;
}

std::vector<std::unique_ptr<Expression>> read_components(const JsonObject& j, const std::string& key, int dim,
                                                         bool allow_null) {
  const auto& raw = j.raw(key);
  const std::string expected = fmt::format("an array of {} entries, each a number or an expression of t, x, y, z{}", dim,
                                           allow_null ? " (or null to leave that component free)" : "");
  if (!raw.is_array() || static_cast<int>(raw.size()) != dim) j.fail(key, "expected " + expected);
  std::vector<std::unique_ptr<Expression>> out;
  for (int k = 0; k < dim; ++k) {
    const auto& v = raw[k];
    if (v.is_null() && allow_null) {
      out.push_back(nullptr);
    } else if (v.is_number()) {
      out.push_back(std::make_unique<Expression>(v.get<Real>()));
    } else if (v.is_string()) {
      try {
        out.push_back(std::make_unique<Expression>(v.get<std::string>(),
                                                   fmt::format("{}: {}[{}]", j.file(), j.path_of(key), k)));
      } catch (const std::invalid_argument& e) {
        j.fail(key, fmt::format("entry {} \"{}\" is not a valid expression: {}", k, v.get<std::string>(), e.what()));
      }
    } else {
      j.fail(key, fmt::format("entry {} is {}; expected {}", k, v.dump(), expected));
    }
  }
  return out;
}

std::vector<Index> select_nodes(const JsonObject& where, const FemMesh& mesh, std::string* boundary_name) {
  const char* keys[] = {"box", "boundary", "side", "tag"};
  int given = 0;
  std::string key;
  for (const char* k : keys)
    if (where.has(k)) ++given, key = k;
  if (given != 1)
    where.fail(given ? key : "boundary",
               "give exactly one of \"boundary\" (or \"side\" / \"tag\"): a name or a list of names, or \"box\": "
               "{\"min\": [...], \"max\": [...]}");
  std::vector<Index> nodes;
  if (key != "box") {
    const auto& raw = where.raw(key);
    std::vector<std::string> names;
    if (raw.is_string()) names.push_back(raw.get<std::string>());
    if (raw.is_array())
      for (const auto& n : raw)
        if (n.is_string()) names.push_back(n.get<std::string>());
    if (names.empty() || (raw.is_array() && names.size() != raw.size()))
      where.fail(key, "expected a boundary name or a non-empty list of names");
    for (const std::string& name : names) {
      if (!mesh.boundary(name)) {
        std::string allowed;
        for (const auto& b : mesh.boundaries) allowed += (allowed.empty() ? "" : ", ") + b.name;
        where.fail(key, fmt::format("no boundary named '{}'; allowed: {}", name, allowed));
      }
      const std::vector<Index> more = mesh.boundary_nodes(name);
      nodes.insert(nodes.end(), more.begin(), more.end());
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    if (boundary_name && names.size() == 1) *boundary_name = names[0];
  } else {
    const JsonObject box = where.object("box");
    const Vec3 lo = read_point(box, "min", mesh.dim), hi = read_point(box, "max", mesh.dim);
    box.finish();
    for (Index n = 0; n < mesh.node_count(); ++n) {
      const Vec3& X = mesh.nodes[n];
      if ((X.head(mesh.dim).array() >= lo.head(mesh.dim).array()).all() &&
          (X.head(mesh.dim).array() <= hi.head(mesh.dim).array()).all())
        nodes.push_back(n);
    }
  }
  where.finish();
  if (nodes.empty()) where.fail(key, "selects no node of the mesh");
  return nodes;
}

}  // namespace moreau
