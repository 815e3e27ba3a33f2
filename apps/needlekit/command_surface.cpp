// `needlekit surface MESH --unit mm [--json] [--geodesic I J]`: reads a body surface (OBJ, STL, PLY, OFF), checks
// that it is usable for patch fitting (manifold, consistently oriented) and reports its size and density; with
// --geodesic, the geodesic distance between two of its vertices.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "commands.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/geometry/geodesic_distance.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/scale_warnings.hpp"
#include "terminal_warnings.hpp"

namespace needlekit::cli {
namespace {

struct SurfaceArguments {
  std::string mesh_path;
  std::string unit;
  bool json = false;
  bool weld = false;
  std::vector<int> geodesic;  // two vertex indices, or empty
};

geometry::SurfaceLocation vertex_location(const geometry::SurfaceMesh& surface, int vertex, const char* what) {
  try {
    return geometry::vertex_location(surface, vertex);
  } catch (const InvalidInput& error) {
    throw InvalidInput(fmt::format("--geodesic: {} {}", what, error.what()));
  }
}

void run_surface(const SurfaceArguments& arguments) {
  // A unit name ("mm") or the length of one file unit ("15.8 mm", for meshes in arbitrary units).
  const bool quantity = arguments.unit.find_first_of("0123456789") != std::string::npos;
  const double unit = quantity ? units::parse_quantity(arguments.unit, units::Dimension::Length, "--unit")
                               : units::unit_factor(arguments.unit, units::Dimension::Length, "--unit");
  if (!(unit > 0)) throw InvalidInput(fmt::format("--unit: '{}' must be a positive length", arguments.unit));
  const auto started = std::chrono::steady_clock::now();
  const geometry::BodySurface body = geometry::read_body_surface(arguments.mesh_path, unit, {.weld = arguments.weld});
  const geometry::SurfaceCheck& check = body.check;
  const geometry::SurfaceMesh& surface = body.surface;
  const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();

  const auto& m = surface.mesh();
  Eigen::AlignedBox3d box;
  for (const auto& v : m.vertices) box.extend(v);
  std::vector<double> edges;
  edges.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles) {
    for (int c = 0; c < 3; ++c) edges.push_back((m.vertices[t[(c + 1) % 3]] - m.vertices[t[c]]).norm());
  }
  std::nth_element(edges.begin(), edges.begin() + static_cast<long>(edges.size() / 2), edges.end());
  constexpr double mm = 1e-3;
  nlohmann::ordered_json out;
  out["mesh"] = arguments.mesh_path;
  out["unit"] = arguments.unit;
  out["vertices"] = surface.vertex_count();
  out["triangles"] = surface.triangle_count();
  out["closed"] = check.closed;
  out["boundary_edges"] = check.boundary_edges;
  out["outer_triangles"] = check.outer_triangles;
  out["degenerate_triangles"] = check.degenerate_triangles;
  out["coincident_vertices"] = check.coincident_vertices;
  out["flipped_inward_normals"] = body.flipped;
  out["area_mm2"] = geometry::surface_area(m) / (mm * mm);
  if (check.closed) out["volume_mm3"] = geometry::signed_volume(m) / (mm * mm * mm);
  out["size_mm"] = {box.sizes().x() / mm, box.sizes().y() / mm, box.sizes().z() / mm};
  out["median_edge_mm"] = edges[edges.size() / 2] / mm;
  out["load_ms"] = load_ms;
  const std::vector<std::string> warnings = io::surface_scale_warnings(m, "--unit");
  out["notes"] = warnings;
  print_warnings(warnings);
  if (arguments.geodesic.size() == 2) {
    const auto from = vertex_location(surface, arguments.geodesic[0], "first");
    const auto to = vertex_location(surface, arguments.geodesic[1], "second");
    const auto d = geometry::geodesic_distance(surface, from, to);
    out["geodesic"] = {{"from_vertex", arguments.geodesic[0]},
                       {"to_vertex", arguments.geodesic[1]},
                       {"status", geometry::to_string(d.status)},
                       {"distance_mm", d.distance / mm},
                       {"euclidean_mm", d.euclidean / mm},
                       {"triangles_crossed", d.path.triangles.size()}};
    if (!d.reason.empty()) out["geodesic"]["reason"] = d.reason;
  }
  if (arguments.json) {
    fmt::print("{}", io::json_text(out));
    return;
  }
  fmt::print("{}: {} vertices, {} triangles, {}, usable (manifold, consistently oriented)\n", arguments.mesh_path,
             surface.vertex_count(), surface.triangle_count(),
             check.closed ? "closed" : fmt::format("open ({} boundary edges)", check.boundary_edges));
  fmt::print("size {:.4g} x {:.4g} x {:.4g} mm, area {:.6g} mm^2, median edge {:.3g} mm, {} degenerate triangles\n",
             box.sizes().x() / mm, box.sizes().y() / mm, box.sizes().z() / mm, out["area_mm2"].get<double>(),
             out["median_edge_mm"].get<double>(), check.degenerate_triangles);
  if (out.contains("geodesic")) {
    const auto& g = out["geodesic"];
    fmt::print("geodesic {} -> {}: {:.6g} mm ({}; straight line {:.6g} mm)\n", arguments.geodesic[0],
               arguments.geodesic[1], g["distance_mm"].get<double>(), g["status"].get<std::string>(),
               g["euclidean_mm"].get<double>());
  }
  if (body.flipped) fmt::print("note: {}\n", body.note);
  if (check.coincident_vertices > 0) {
    fmt::print("note: {} vertices share a position with another: seams split in the file; --weld merges them\n",
               check.coincident_vertices);
  }
  fmt::print("read and indexed in {:.0f} ms\n", load_ms);
}

}  // namespace

void add_surface_command(CLI::App& app) {
  auto arguments = std::make_shared<SurfaceArguments>();
  CLI::App* command = app.add_subcommand(
      "surface", "Check a body surface mesh (OBJ, STL, PLY, OFF) for patch fitting and report its size and density");
  command->add_option("MESH", arguments->mesh_path, "triangle mesh file: .obj, .stl, .ply or .off")->required();
  command
      ->add_option("--unit", arguments->unit,
                   "length unit of the file's coordinates: nm, um, mm, cm, m, or the length of one file unit "
                   "(\"15.8 mm\" for the skull mesh's arbitrary units)")
      ->required();
  command->add_flag("--json", arguments->json, "print the report as JSON (lengths in mm)");
  command->add_flag("--weld", arguments->weld,
                    "merge vertices with identical coordinates first (meshes exported with split seams)");
  command->add_option("--geodesic", arguments->geodesic, "geodesic distance between two vertices (0-based indices)")
      ->expected(2)
      ->type_name("I J");
  command->callback([arguments] { run_surface(*arguments); });
}

}  // namespace needlekit::cli
