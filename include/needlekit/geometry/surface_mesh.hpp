// A free-form body surface (dissertation §5.6): a triangle mesh with its triangle adjacency through shared reversed
// edges, face and vertex normals, and an AABB tree for closest-point and ray queries (CGAL inside
// surface_mesh.cpp only). Coordinates in metres once loaded (the file's unit is stated by the caller).
#pragma once
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::geometry {

struct SurfaceCheck {
  bool edge_manifold = false;           // no edge used by more than two triangles
  bool consistently_oriented = false;   // every interior edge used once in each direction
  bool closed = false;
  int boundary_edges = 0;
  int non_manifold_edges = 0;
  int inconsistent_edges = 0;
  int degenerate_triangles = 0;
  int outer_triangles = 0;              // triangles with at least one boundary edge (§5.6); the rest are inner
  int coincident_vertices = 0;          // vertices at the position of another (split seams: see welded_mesh)
  std::string problems;                 // empty when usable; else a readable list of what is wrong
};

struct ClosestPoint {
  Eigen::Vector3d point;        // m, on the surface
  int triangle = -1;
  Eigen::Vector3d barycentric;  // of `point` in `triangle`
  double distance = 0;          // m
};

struct RayHit {
  Eigen::Vector3d point;
  int triangle = -1;
  double distance = 0;          // m, along the (unit) ray direction from its origin
};

class SurfaceMesh {
public:
  // Builds adjacency, normals and the AABB tree. Throws InvalidInput if the mesh is empty, non-manifold or
  // inconsistently oriented (the message says what and where).
  explicit SurfaceMesh(TriangleMesh mesh);
  ~SurfaceMesh();
  SurfaceMesh(SurfaceMesh&&) noexcept;
  SurfaceMesh& operator=(SurfaceMesh&&) noexcept;

  const TriangleMesh& mesh() const;
  int triangle_count() const;
  int vertex_count() const;
  // The triangle across edge e of triangle t (edge e joins corners e and (e+1)%3), or -1 on the boundary.
  int neighbor(int triangle, int edge) const;
  // A triangle that uses the vertex (the first in the mesh's order), or -1 for a vertex no triangle uses.
  int vertex_triangle(int vertex) const;
  // Inner triangle (§5.6, Fig 5.9): all three edges shared with neighbours; an outer one touches the boundary.
  bool is_inner(int triangle) const;
  const Eigen::Vector3d& face_normal(int triangle) const;   // unit, outward
  const Eigen::Vector3d& vertex_normal(int vertex) const;   // unit, angle-weighted
  Eigen::Vector3d interpolated_normal(int triangle, const Eigen::Vector3d& barycentric) const;
  const SurfaceCheck& check() const;

  ClosestPoint closest_point(const Eigen::Vector3d& query) const;
  // First intersection of the ray origin + s*direction, s > 0; empty if it misses.
  std::optional<RayHit> first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The manifold/orientation check alone (indices out of range or non-finite coordinates still throw InvalidInput),
// for reporting what is wrong with a mesh that the SurfaceMesh constructor would refuse.
SurfaceCheck surface_check(const TriangleMesh& mesh);

// Reads OBJ, STL (ASCII or binary), PLY or OFF by the file's extension, scaling coordinates by `unit_to_metre`
// (e.g. 1e-3 for a file in mm). Throws IoError naming the file (and line where the reader reports one); a directory
// or a missing file is an IoError too.
TriangleMesh read_triangle_mesh(const std::filesystem::path& path, double unit_to_metre);

enum class MeshFormat { Obj, Stl, Ply, Off };
inline constexpr EnumTable<MeshFormat, 4> kMeshFormatNames{{
    {MeshFormat::Obj, "OBJ", "Wavefront OBJ (.obj)"},
    {MeshFormat::Stl, "STL", "STL, ASCII or binary (.stl)"},
    {MeshFormat::Ply, "PLY", "Stanford PLY, ASCII or binary (.ply)"},
    {MeshFormat::Off, "OFF", "Object File Format (.off)"},
}};
std::string_view to_string(MeshFormat format);
// The same from the file's bytes; `source_name` stands for the file in messages.
TriangleMesh parse_triangle_mesh(std::string_view bytes, MeshFormat format, std::string_view source_name,
                                 double unit_to_metre);

}  // namespace needlekit::geometry
