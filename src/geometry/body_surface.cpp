#include "needlekit/geometry/body_surface.hpp"

#include <fmt/format.h>
#include <utility>
#include <vector>

#include "needlekit/core/errors.hpp"

namespace needlekit::geometry {
namespace {

// How many degenerate triangles the message names.
constexpr std::size_t kExamples = 3;

std::string degenerate_message(const TriangleMesh& mesh, const std::vector<int>& degenerate) {
  std::string where;
  for (std::size_t i = 0; i < std::min(degenerate.size(), kExamples); ++i) {
    const auto& t = mesh.triangles[degenerate[i]];
    const Eigen::Vector3d centre = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3 * 1e3;
    where += fmt::format("{}triangle {} (vertices {}, {}, {}) at ({:.6g}, {:.6g}, {:.6g}) mm", i ? "; " : "",
                         degenerate[i], t[0], t[1], t[2], centre.x(), centre.y(), centre.z());
  }
  return fmt::format("{} of {} triangles are degenerate (zero area): {}{}; expected none: remove them or collapse "
                     "their shortest edges before fitting a patch",
                     degenerate.size(), mesh.triangles.size(), where, degenerate.size() > kExamples ? "; ..." : "");
}

}  // namespace

BodySurface body_surface(TriangleMesh mesh, std::string_view source_name, const BodySurfaceOptions& options) {
  if (options.weld) mesh = welded_mesh(mesh);
  const SurfaceCheck check = surface_check(mesh);
  if (!check.problems.empty()) {
    throw InvalidInput(fmt::format("{}: not usable as a body surface: {}", source_name, check.problems));
  }
  const std::vector<int> degenerate = degenerate_triangles(mesh);
  if (!degenerate.empty()) {
    throw InvalidInput(fmt::format("{}: not usable as a body surface: {}", source_name,
                                   degenerate_message(mesh, degenerate)));
  }
  bool flipped = false;
  std::string note;
  if (check.closed && check.consistently_oriented) {
    const double volume = signed_volume(mesh);
    if (volume < 0) {
      for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
      flipped = true;
      note = fmt::format("{}: the closed surface's normals pointed inwards (enclosed volume {:.6g} mm^3); every "
                         "triangle was reversed so that they point outwards",
                         source_name, volume * 1e9);
    }
  }
  return {SurfaceMesh(std::move(mesh)), check, flipped, std::move(note)};
}

BodySurface read_body_surface(const std::filesystem::path& path, double unit_to_metre,
                              const BodySurfaceOptions& options) {
  return body_surface(read_triangle_mesh(path, unit_to_metre), path.string(), options);
}

}  // namespace needlekit::geometry
