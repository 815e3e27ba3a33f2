// A triangle surface mesh (vertices + index triples) and its basic measures.
#pragma once
#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <string_view>
#include <vector>

namespace needlekit::geometry {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside (outward normals)
};

// Signed enclosed volume by the divergence theorem (positive for a closed mesh with outward normals).
double signed_volume(const TriangleMesh& mesh);
// Total area.
double surface_area(const TriangleMesh& mesh);

struct MeshTopologyReport {
  bool closed = false;                 // every edge shared by exactly two triangles
  bool consistently_oriented = false;  // every shared edge used once in each direction
  int boundary_edges = 0;
  int non_manifold_edges = 0;          // edges used by more than two triangles
  int degenerate_triangles = 0;        // zero area (relative to the mesh size)
};
MeshTopologyReport topology_report(const TriangleMesh& mesh);
// The triangles with zero area (a repeated corner, or an area below 1e-14 of the squared bounding-box diagonal), in
// order.
std::vector<int> degenerate_triangles(const TriangleMesh& mesh);

// The mesh with vertices of identical coordinates merged into one (kept in order of first use by the triangles;
// vertices that no triangle uses are dropped). Use it on meshes exported with split vertices along seams.
TriangleMesh welded_mesh(const TriangleMesh& mesh);

// Writes binary STL (unit: the caller's; needlekit writes metres unless told otherwise via `scale`). Writes to a
// temporary file and renames, so no partial file is left on failure. Throws IoError.
void write_stl(const TriangleMesh& mesh, const std::filesystem::path& path, double scale = 1.0);
// Reads ASCII or binary STL, merging identical vertices. Throws IoError naming the file.
TriangleMesh read_stl(const std::filesystem::path& path, double scale = 1.0);
// The same from the file's bytes; `source_name` stands for the file in messages.
TriangleMesh parse_stl(std::string_view bytes, std::string_view source_name, double scale = 1.0);

}  // namespace needlekit::geometry
