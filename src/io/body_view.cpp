#include "needlekit/io/body_view.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <vector>

#include "needlekit/geometry/vertex_clustering.hpp"
#include "needlekit/geometry/vertex_pick.hpp"
#include "needlekit/io/view_arrays.hpp"

namespace needlekit::io {

nlohmann::json body_view(const std::string& name, const geometry::SurfaceMesh& surface,
                         const BodyViewOptions& options) {
  const geometry::TriangleMesh& full = surface.mesh();
  const geometry::ClusteredMesh drawn = geometry::clustered_mesh(full, options.max_triangles);
  // Positions, and the full mesh's normals at the vertices drawn: lit by these, the slivers that clustering folds
  // over shade as the surface they stand for, not as dark specks.
  std::vector<float> positions, normals;
  const auto append = [](std::vector<float>& to, const Eigen::Vector3d& v) {
    to.insert(to.end(), {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
  };
  for (std::size_t k = 0; k < drawn.mesh.vertices.size(); ++k) {
    append(positions, drawn.mesh.vertices[k]);
    append(normals, surface.vertex_normal(drawn.source_vertex[k]));
  }
  std::vector<std::uint32_t> indices, vertex_ids(drawn.source_vertex.begin(), drawn.source_vertex.end());
  for (const auto& t : drawn.mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
  nlohmann::json notes = nlohmann::json::array();
  if (drawn.cell_size > 0) {
    notes.push_back(fmt::format("decimated by vertex clustering on {:.3g} mm cells: {} of the mesh's {} triangles "
                                "drawn; every vertex drawn is a vertex of the mesh",
                                drawn.cell_size * 1e3, drawn.mesh.triangles.size(), full.triangles.size()));
  }
  nlohmann::json view = {{"format", "needlekit-view/1"}, {"kind", "body"}, {"name", name}};
  view["title"] = fmt::format("{}: click on the surface to place the patch's centre", name);
  view["steps"] = nlohmann::json::array({{{"label", "body surface"}}});
  view["steps_total"] = 1;
  view["surface"] = {{"region", "whole body"},
                     {"vertices", drawn.mesh.vertices.size()},
                     {"triangles", drawn.mesh.triangles.size()},
                     {"indices", uint32_array(indices)},
                     {"positions", float32_array(positions)},
                     {"normals", float32_array(normals)},
                     {"vertex_ids", uint32_array(vertex_ids)},
                     {"fields", nlohmann::json::array()}};
  view["full_mesh"] = {{"vertices", full.vertices.size()}, {"triangles", full.triangles.size()}};
  view["cell_size_m"] = drawn.cell_size;
  view["notes"] = notes;
  return view;
}

namespace {

nlohmann::json point_json(const Eigen::Vector3d& p) { return nlohmann::json::array({p.x(), p.y(), p.z()}); }

}  // namespace

nlohmann::json body_pick(const geometry::SurfaceMesh& surface, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& direction) {
  const std::optional<geometry::VertexPick> pick = geometry::pick_vertex(surface, origin, direction);
  if (!pick) return {{"hit", false}};
  return {{"hit", true},
          {"vertex", pick->vertex},
          {"triangle", pick->triangle},
          {"position_m", point_json(surface.mesh().vertices[static_cast<std::size_t>(pick->vertex)])},
          {"point_m", point_json(pick->point)},
          {"normal", point_json(surface.vertex_normal(pick->vertex))}};
}

}  // namespace needlekit::io
