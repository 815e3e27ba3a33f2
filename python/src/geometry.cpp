// needlekit/geometry: triangle meshes (numpy vertices and triangles), body surfaces with closest-point and ray
// queries, straightest geodesics and geodesic distances.
#include "common.hpp"
#include "enum_binding.hpp"
#include "needlekit/geometry/geodesic_distance.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::python {

void bind_geometry(py::module_& m) {
  using namespace geometry;
  py::class_<TriangleMesh>(
      m, "TriangleMesh",
      "A triangle surface mesh: vertices (N, 3) in m and triangles (M, 3) of vertex indices "
      "(counter-clockwise seen from outside). Read-only numpy views; build a new mesh to change it.")
      .def(py::init([](py::handle vertices, py::handle triangles) {
             TriangleMesh mesh{points_from(vertices, "vertices"), index_rows_from<3>(triangles, "triangles")};
             for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
               for (int k = 0; k < 3; ++k)
                 if (mesh.triangles[t][k] >= static_cast<int>(mesh.vertices.size()))
                   throw_invalid("triangles[" + std::to_string(t) + ", " + std::to_string(k) + "]: vertex " +
                                 std::to_string(mesh.triangles[t][k]) + " does not exist (" +
                                 std::to_string(mesh.vertices.size()) + " vertices)");
             return mesh;
           }),
           py::arg("vertices"), py::arg("triangles"))
      .def_property_readonly(
          "vertices", [](py::object self) { return points_view(self.cast<const TriangleMesh&>().vertices, self); },
          "m, (N, 3)")
      .def_property_readonly(
          "triangles", [](py::object self) { return index_view(self.cast<const TriangleMesh&>().triangles, self); },
          "(M, 3)");
  m.def("signed_volume", &signed_volume, py::arg("mesh"), "m^3, positive for a closed outward mesh.");
  m.def("surface_area", &surface_area, py::arg("mesh"), "m^2");
  m.def("welded_mesh", &welded_mesh, py::arg("mesh"), "The mesh with coincident vertices merged.");
  m.def("read_triangle_mesh", &read_triangle_mesh, py::arg("path"), py::arg("unit_to_metre"),
        "Reads OBJ, STL, PLY or OFF; coordinates times unit_to_metre (1e-3 for mm). Raises IoError naming the file.");
  m.def("write_stl", &write_stl, py::arg("mesh"), py::arg("path"), py::arg("scale") = 1.0,
        "Binary STL, written to a temporary name and renamed.");
  m.def("read_stl", &read_stl, py::arg("path"), py::arg("scale") = 1.0);

  py::class_<SurfaceCheck>(m, "SurfaceCheck")
      .def_readonly("edge_manifold", &SurfaceCheck::edge_manifold)
      .def_readonly("consistently_oriented", &SurfaceCheck::consistently_oriented)
      .def_readonly("closed", &SurfaceCheck::closed)
      .def_readonly("boundary_edges", &SurfaceCheck::boundary_edges)
      .def_readonly("non_manifold_edges", &SurfaceCheck::non_manifold_edges)
      .def_readonly("inconsistent_edges", &SurfaceCheck::inconsistent_edges)
      .def_readonly("degenerate_triangles", &SurfaceCheck::degenerate_triangles)
      .def_readonly("outer_triangles", &SurfaceCheck::outer_triangles)
      .def_readonly("coincident_vertices", &SurfaceCheck::coincident_vertices)
      .def_readonly("problems", &SurfaceCheck::problems);
  m.def("surface_check", &surface_check, py::arg("mesh"));
  py::class_<ClosestPoint>(m, "ClosestPoint")
      .def_readonly("point", &ClosestPoint::point, "m")
      .def_readonly("triangle", &ClosestPoint::triangle)
      .def_readonly("barycentric", &ClosestPoint::barycentric)
      .def_readonly("distance", &ClosestPoint::distance, "m");
  py::class_<RayHit>(m, "RayHit")
      .def_readonly("point", &RayHit::point, "m")
      .def_readonly("triangle", &RayHit::triangle)
      .def_readonly("distance", &RayHit::distance, "m");
  py::class_<SurfaceMesh>(m, "SurfaceMesh",
                          "A body surface (§5.6) with adjacency, normals and an AABB tree (m). Raises InvalidInput "
                          "for an empty, non-manifold or inconsistently oriented mesh.")
      .def(py::init<TriangleMesh>(), py::arg("mesh"))
      .def("mesh", &SurfaceMesh::mesh, py::return_value_policy::reference_internal)
      .def("triangle_count", &SurfaceMesh::triangle_count)
      .def("vertex_count", &SurfaceMesh::vertex_count)
      .def("neighbor", &SurfaceMesh::neighbor, py::arg("triangle"), py::arg("edge"))
      .def("is_inner", &SurfaceMesh::is_inner, py::arg("triangle"))
      .def("face_normal", &SurfaceMesh::face_normal, py::arg("triangle"))
      .def("vertex_normal", &SurfaceMesh::vertex_normal, py::arg("vertex"))
      .def("check", &SurfaceMesh::check, py::return_value_policy::reference_internal)
      .def(
          "closest_point",
          [](const SurfaceMesh& s, py::handle q) {
            return s.closest_point(
                points_from(py::module_::import("numpy").attr("reshape")(q, py::make_tuple(1, 3)), "query")[0]);
          },
          py::arg("query"), "The closest surface point to a point (m).")
      .def(
          "first_hit",
          [](const SurfaceMesh& s, py::handle origin, py::handle direction) {
            const auto np = py::module_::import("numpy");
            return s.first_hit(points_from(np.attr("reshape")(origin, py::make_tuple(1, 3)), "origin")[0],
                               points_from(np.attr("reshape")(direction, py::make_tuple(1, 3)), "direction")[0]);
          },
          py::arg("origin"), py::arg("direction"), "First hit of the ray, or None.");

  py::class_<SurfaceLocation> location(m, "SurfaceLocation", "A triangle and barycentric coordinates in it.");
  location
      .def(py::init([](int triangle, const Eigen::Vector3d& barycentric) {
             return SurfaceLocation{triangle, barycentric};
           }),
           py::arg("triangle"), py::arg("barycentric") = Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3))
      .def_readwrite("triangle", &SurfaceLocation::triangle)
      .def_readwrite("barycentric", &SurfaceLocation::barycentric);
  m.def("surface_location", &surface_location, py::arg("closest_point"));
  m.def("vertex_location", &vertex_location, py::arg("surface"), py::arg("vertex"));
  m.def("position", &position, py::arg("surface"), py::arg("location"), "m");

  bind_enum<geometry::kPathStatusNames>(m, "PathStatus", "How a surface path ended.");
  py::class_<TraceOptions> trace(m, "TraceOptions");
  def_keyword_init<TraceOptions>(trace);
  trace.def_readwrite("max_steps", &TraceOptions::max_steps)
      .def_readwrite("vertex_tolerance", &TraceOptions::vertex_tolerance)
      .def_readwrite("degenerate_sine", &TraceOptions::degenerate_sine);
  py::class_<VertexCrossing>(m, "VertexCrossing")
      .def_readonly("vertex", &VertexCrossing::vertex)
      .def_readonly("total_angle", &VertexCrossing::total_angle, "rad");
  py::class_<SurfacePath>(m, "SurfacePath", "A walk on the surface; points (K, 3) in m as a numpy view.")
      .def_readonly("status", &SurfacePath::status)
      .def_readonly("reason", &SurfacePath::reason)
      .def_readonly("end", &SurfacePath::end)
      .def_readonly("end_point", &SurfacePath::end_point, "m")
      .def_readonly("end_direction", &SurfacePath::end_direction)
      .def_readonly("length", &SurfacePath::length, "m")
      .def_property_readonly(
          "points", [](py::object self) { return points_view(self.cast<const SurfacePath&>().points, self); },
          "m, (K, 3)")
      .def_property_readonly(
          "triangles", [](py::object self) { return values_view(self.cast<const SurfacePath&>().triangles, self); })
      .def_readonly("vertex_crossings", &SurfacePath::vertex_crossings);
  m.def(
      "straightest_geodesic",
      [](const SurfaceMesh& s, const SurfaceLocation& start, const Eigen::Vector3d& direction, py::handle length,
         const TraceOptions& o) {
        return straightest_geodesic(s, start, direction, quantity(length, Dimension::Length, "length"), o);
      },
      py::arg("surface"), py::arg("start"), py::arg("direction"), py::arg("length"),
      py::arg("options") = TraceOptions{},
      "The straightest geodesic (Polthier & Schmies 1998) from `start` along `direction` for `length` (m or \"5 "
      "mm\").");

  py::class_<GeodesicDistanceOptions> distance_options(m, "GeodesicDistanceOptions");
  def_keyword_init<GeodesicDistanceOptions>(distance_options);
  distance_options.def_readwrite("max_iterations", &GeodesicDistanceOptions::max_iterations)
      .def_readwrite("tolerance", &GeodesicDistanceOptions::tolerance)
      .def_readwrite("extra_shots", &GeodesicDistanceOptions::extra_shots)
      .def_readwrite("graph_fallback", &GeodesicDistanceOptions::graph_fallback)
      .def_readwrite("saddle_detour", &GeodesicDistanceOptions::saddle_detour)
      .def_readwrite("trace", &GeodesicDistanceOptions::trace);
  bind_enum<geometry::kDistanceStatusNames>(m, "DistanceStatus", "Whether a geodesic distance was found.");
  py::class_<GeodesicDistance>(m, "GeodesicDistance")
      .def_readonly("status", &GeodesicDistance::status)
      .def_readonly("reason", &GeodesicDistance::reason)
      .def_readonly("distance", &GeodesicDistance::distance, "m")
      .def_readonly("euclidean", &GeodesicDistance::euclidean, "m")
      .def_readonly("miss", &GeodesicDistance::miss, "m")
      .def_readonly("iterations", &GeodesicDistance::iterations)
      .def_readonly("graph_distance", &GeodesicDistance::graph_distance, "m")
      .def_readonly("via_vertex", &GeodesicDistance::via_vertex)
      .def_readonly("path", &GeodesicDistance::path);
  m.def("geodesic_distance", &geodesic_distance, py::arg("surface"), py::arg("from_"), py::arg("to"),
        py::arg("options") = GeodesicDistanceOptions{}, "Geodesic distance (m) by shooting straightest geodesics.");
}

}  // namespace needlekit::python
