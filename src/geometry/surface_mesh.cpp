// SurfaceMesh: adjacency through shared reversed edges, normals, the manifold/orientation check (dissertation §5.6,
// Fig 5.9) and CGAL's AABB tree for closest-point and ray queries. CGAL stays inside this file.
#include "needlekit/geometry/surface_mesh.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "needlekit/core/errors.hpp"

namespace needlekit::geometry {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using CgalPoint = Kernel::Point_3;
using CgalTriangle = Kernel::Triangle_3;
using CgalRay = Kernel::Ray_3;
using TriangleIterator = std::vector<CgalTriangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// Same threshold as topology_report (triangle_mesh.cpp): a triangle with area below this fraction of the squared
// bounding-box diagonal is degenerate.
constexpr double kDegenerateRelativeArea = 1e-14;
// How many example edges/triangles the problem list names per kind.
constexpr int kExamples = 3;

CgalPoint to_cgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
Eigen::Vector3d to_eigen(const CgalPoint& p) { return {p.x(), p.y(), p.z()}; }

// Barycentric coordinates of p (assumed in the plane of a, b, c) by the least-squares projection; for a degenerate
// triangle the coordinates of the nearest vertex.
Eigen::Vector3d barycentric_of(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d e0 = b - a, e1 = c - a, v = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = v.dot(e0), d21 = v.dot(e1);
  const double det = d00 * d11 - d01 * d01;
  if (!(det > 1e-30 * (d00 * d11)) || d00 == 0 || d11 == 0) {
    const double da = (p - a).squaredNorm(), db = (p - b).squaredNorm(), dc = (p - c).squaredNorm();
    if (da <= db && da <= dc) return {1, 0, 0};
    return db <= dc ? Eigen::Vector3d(0, 1, 0) : Eigen::Vector3d(0, 0, 1);
  }
  const double w1 = (d11 * d20 - d01 * d21) / det;
  const double w2 = (d00 * d21 - d01 * d20) / det;
  return {1 - w1 - w2, w1, w2};
}

}  // namespace

struct SurfaceMesh::Impl {
  TriangleMesh mesh;
  std::vector<std::array<int, 3>> neighbors;
  std::vector<int> vertex_triangles;  // a triangle using each vertex, or -1
  std::vector<Eigen::Vector3d> face_normals;
  std::vector<Eigen::Vector3d> vertex_normals;
  SurfaceCheck check;
  double diagonal = 0;
  std::vector<CgalTriangle> cgal_triangles;
  Tree tree;
};

namespace {

struct DirectedEdge {
  std::uint64_t key;  // (min vertex, max vertex)
  int triangle;
  int edge;           // 0..2: corners edge, edge+1
  bool forward;       // from min to max
};

std::string edge_text(const DirectedEdge& e, const TriangleMesh& mesh) {
  const auto& t = mesh.triangles[e.triangle];
  return fmt::format("{}-{}", t[e.edge], t[(e.edge + 1) % 3]);
}

void append_examples(std::string& out, std::string_view what, int count, const std::vector<std::string>& examples) {
  if (count == 0) return;
  out += fmt::format("{} {}", count, what);
  if (!examples.empty()) {
    out += " (e.g. ";
    for (std::size_t i = 0; i < examples.size(); ++i) out += (i ? ", " : "") + examples[i];
    out += count > static_cast<int>(examples.size()) ? ", ...)" : ")";
  }
  out += "; ";
}

// The triangle adjacency through shared reversed edges, and the edge part of the check (Fig 5.9: each triangle is
// linked to its neighbours through its three edges; triangles with fewer than three neighbours are "outer" ones).
SurfaceCheck adjacency_check(const TriangleMesh& mesh, std::vector<std::array<int, 3>>& neighbors) {
  const auto& tris = mesh.triangles;
  const int n = static_cast<int>(tris.size());
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * tris.size());
  for (int t = 0; t < n; ++t) {
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::uint64_t>(tris[t][e]);
      const auto b = static_cast<std::uint64_t>(tris[t][(e + 1) % 3]);
      edges.push_back({(std::min(a, b) << 32) | std::max(a, b), t, e, a < b});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
    return x.key != y.key ? x.key < y.key : (x.triangle != y.triangle ? x.triangle < y.triangle : x.edge < y.edge);
  });
  neighbors.assign(tris.size(), {-1, -1, -1});
  SurfaceCheck check;
  std::vector<std::string> non_manifold_examples, inconsistent_examples;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    const std::size_t uses = j - i;
    if (uses == 1) {
      ++check.boundary_edges;
    } else if (uses == 2) {
      const DirectedEdge& x = edges[i];
      const DirectedEdge& y = edges[i + 1];
      if (x.forward == y.forward) {
        ++check.inconsistent_edges;
        if (static_cast<int>(inconsistent_examples.size()) < kExamples) {
          inconsistent_examples.push_back(
              fmt::format("edge {} in triangles {} and {}", edge_text(x, mesh), x.triangle, y.triangle));
        }
      }
      // Linked even when inconsistent, so the check can still be read; the constructor refuses such meshes.
      neighbors[x.triangle][x.edge] = y.triangle;
      neighbors[y.triangle][y.edge] = x.triangle;
    } else {
      ++check.non_manifold_edges;
      if (static_cast<int>(non_manifold_examples.size()) < kExamples) {
        std::string users;
        for (std::size_t k = i; k < j; ++k) users += fmt::format("{}{}", k > i ? ", " : "", edges[k].triangle);
        non_manifold_examples.push_back(
            fmt::format("edge {} in {} triangles: {}", edge_text(edges[i], mesh), uses, users));
      }
    }
    i = j;
  }
  for (const auto& n : neighbors) check.outer_triangles += (n[0] < 0 || n[1] < 0 || n[2] < 0);
  check.edge_manifold = check.non_manifold_edges == 0;
  check.consistently_oriented = check.inconsistent_edges == 0 && check.edge_manifold;
  check.closed = check.boundary_edges == 0 && check.edge_manifold;
  append_examples(check.problems, "non-manifold edges (used by more than two triangles)", check.non_manifold_edges,
                  non_manifold_examples);
  append_examples(check.problems,
                  "inconsistently oriented edges (two triangles traverse the edge in the same direction: one of "
                  "them is flipped)",
                  check.inconsistent_edges, inconsistent_examples);
  if (!check.problems.empty()) check.problems.resize(check.problems.size() - 2);  // the trailing "; "
  // Vertices sharing a position: sort by coordinates and count repeats.
  std::vector<int> order(mesh.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  const auto less = [&](int x, int y) {
    const auto& p = mesh.vertices[x];
    const auto& q = mesh.vertices[y];
    return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) {
    check.coincident_vertices += mesh.vertices[order[i]] == mesh.vertices[order[i - 1]];
  }
  return check;
}

void check_indices_and_coordinates(const TriangleMesh& mesh) {
  if (mesh.triangles.empty() || mesh.vertices.empty()) {
    throw InvalidInput(fmt::format("surface mesh: empty ({} vertices, {} triangles); expected at least one triangle",
                                   mesh.vertices.size(), mesh.triangles.size()));
  }
  const auto nv = static_cast<long long>(mesh.vertices.size());
  if (nv >= (1LL << 31)) throw InvalidInput("surface mesh: more than 2^31 vertices");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int index : mesh.triangles[t]) {
      if (index < 0 || index >= nv) {
        throw InvalidInput(fmt::format(
            "surface mesh: triangle {} refers to vertex {}, expected an index in [0, {})", t, index, nv));
      }
    }
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw InvalidInput(fmt::format("surface mesh: vertex {} has a non-finite coordinate", i));
    }
  }
}

struct Normals {
  std::vector<Eigen::Vector3d> face;
  std::vector<Eigen::Vector3d> vertex;
  double diagonal = 0;  // of the bounding box
  int degenerate_triangles = 0;
};

Normals normals_of(const TriangleMesh& mesh) {
  Normals impl;
  const auto& v = mesh.vertices;
  const auto& tris = mesh.triangles;
  Eigen::AlignedBox3d box;
  for (const auto& p : v) box.extend(p);
  impl.diagonal = box.isEmpty() ? 0.0 : box.diagonal().norm();
  const double min_area = kDegenerateRelativeArea * impl.diagonal * impl.diagonal;

  impl.face.assign(tris.size(), Eigen::Vector3d::Zero());
  impl.vertex.assign(v.size(), Eigen::Vector3d::Zero());
  std::vector<bool> degenerate(tris.size(), false);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const auto& tri = tris[t];
    const Eigen::Vector3d twice_area = (v[tri[1]] - v[tri[0]]).cross(v[tri[2]] - v[tri[0]]);
    const double area = 0.5 * twice_area.norm();
    if (!(area > min_area) || tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      degenerate[t] = true;
      ++impl.degenerate_triangles;
      continue;
    }
    const Eigen::Vector3d n = twice_area / (2 * area);
    impl.face[t] = n;
    // Angle-weighted vertex normals (Thürmer & Wüthrich 1998): the sum of the incident face normals weighted by
    // the triangle's interior angle at the vertex.
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d e1 = v[tri[(c + 1) % 3]] - v[tri[c]];
      const Eigen::Vector3d e2 = v[tri[(c + 2) % 3]] - v[tri[c]];
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      impl.vertex[tri[c]] += angle * n;
    }
  }
  for (auto& n : impl.vertex) {
    const double len = n.norm();
    if (len > 0) n /= len;
  }
  // A degenerate triangle has no plane of its own: its normal is the normalised sum of its corners' normals.
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (!degenerate[t]) continue;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int c : tris[t]) n += impl.vertex[c];
    if (n.norm() > 0) impl.face[t] = n.normalized();
  }
  return impl;
}

}  // namespace

SurfaceCheck surface_check(const TriangleMesh& mesh) {
  check_indices_and_coordinates(mesh);
  std::vector<std::array<int, 3>> neighbors;
  SurfaceCheck check = adjacency_check(mesh, neighbors);
  check.degenerate_triangles = topology_report(mesh).degenerate_triangles;
  return check;
}

SurfaceMesh::SurfaceMesh(TriangleMesh mesh) : impl_(std::make_unique<Impl>()) {
  check_indices_and_coordinates(mesh);
  impl_->mesh = std::move(mesh);
  impl_->check = adjacency_check(impl_->mesh, impl_->neighbors);
  if (!impl_->check.problems.empty()) {
    throw InvalidInput(fmt::format("surface mesh ({} vertices, {} triangles) is not usable: {}",
                                   impl_->mesh.vertices.size(), impl_->mesh.triangles.size(),
                                   impl_->check.problems));
  }
  impl_->vertex_triangles.assign(impl_->mesh.vertices.size(), -1);
  for (int t = static_cast<int>(impl_->mesh.triangles.size()) - 1; t >= 0; --t) {
    for (int v : impl_->mesh.triangles[t]) impl_->vertex_triangles[v] = t;
  }
  Normals normals = normals_of(impl_->mesh);
  impl_->face_normals = std::move(normals.face);
  impl_->vertex_normals = std::move(normals.vertex);
  impl_->diagonal = normals.diagonal;
  impl_->check.degenerate_triangles = normals.degenerate_triangles;

  const auto& v = impl_->mesh.vertices;
  impl_->cgal_triangles.reserve(impl_->mesh.triangles.size());
  for (const auto& t : impl_->mesh.triangles) {
    impl_->cgal_triangles.emplace_back(to_cgal(v[t[0]]), to_cgal(v[t[1]]), to_cgal(v[t[2]]));
  }
  impl_->tree.insert(impl_->cgal_triangles.cbegin(), impl_->cgal_triangles.cend());
  // Built eagerly so that const queries are safe from several threads at once.
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

SurfaceMesh::~SurfaceMesh() = default;
SurfaceMesh::SurfaceMesh(SurfaceMesh&&) noexcept = default;
SurfaceMesh& SurfaceMesh::operator=(SurfaceMesh&&) noexcept = default;

const TriangleMesh& SurfaceMesh::mesh() const { return impl_->mesh; }
int SurfaceMesh::triangle_count() const { return static_cast<int>(impl_->mesh.triangles.size()); }
int SurfaceMesh::vertex_count() const { return static_cast<int>(impl_->mesh.vertices.size()); }
int SurfaceMesh::neighbor(int triangle, int edge) const { return impl_->neighbors.at(triangle).at(edge); }
int SurfaceMesh::vertex_triangle(int vertex) const { return impl_->vertex_triangles.at(vertex); }
bool SurfaceMesh::is_inner(int triangle) const {
  const auto& n = impl_->neighbors.at(triangle);
  return n[0] >= 0 && n[1] >= 0 && n[2] >= 0;
}
const Eigen::Vector3d& SurfaceMesh::face_normal(int triangle) const { return impl_->face_normals.at(triangle); }
const Eigen::Vector3d& SurfaceMesh::vertex_normal(int vertex) const { return impl_->vertex_normals.at(vertex); }
const SurfaceCheck& SurfaceMesh::check() const { return impl_->check; }

Eigen::Vector3d SurfaceMesh::interpolated_normal(int triangle, const Eigen::Vector3d& barycentric) const {
  const auto& t = impl_->mesh.triangles.at(triangle);
  const Eigen::Vector3d n = barycentric[0] * impl_->vertex_normals[t[0]] +
                            barycentric[1] * impl_->vertex_normals[t[1]] +
                            barycentric[2] * impl_->vertex_normals[t[2]];
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : impl_->face_normals[triangle];
}

ClosestPoint SurfaceMesh::closest_point(const Eigen::Vector3d& query) const {
  if (!query.allFinite()) throw InvalidInput("closest_point: the query point has a non-finite coordinate");
  const auto [point, id] = impl_->tree.closest_point_and_primitive(to_cgal(query));
  ClosestPoint result;
  result.point = to_eigen(point);
  result.triangle = static_cast<int>(id - impl_->cgal_triangles.cbegin());
  const auto& t = impl_->mesh.triangles[result.triangle];
  const auto& v = impl_->mesh.vertices;
  result.barycentric = barycentric_of(result.point, v[t[0]], v[t[1]], v[t[2]]);
  result.distance = (query - result.point).norm();
  return result;
}

std::optional<RayHit> SurfaceMesh::first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
  const double length = direction.norm();
  if (!origin.allFinite() || !direction.allFinite() || !(length > 0)) {
    throw InvalidInput("first_hit: the ray needs a finite origin and a non-zero finite direction");
  }
  const Eigen::Vector3d unit = direction / length;
  const CgalRay ray(to_cgal(origin), to_cgal(origin + unit * std::max(impl_->diagonal, 1.0)));
  // A ray starting on the surface would hit its own triangle at s = 0; such triangles are skipped (s > 0). So are
  // zero-area triangles: CGAL's ray-triangle intersection requires a non-degenerate triangle (a precondition that
  // Release builds do not check).
  const double touch = 1e-12 * std::max(impl_->diagonal, 1e-300);
  const auto skipped = [&](TriangleIterator id) {
    return id->is_degenerate() || CGAL::squared_distance(*id, ray.source()) <= touch * touch;
  };
  const auto hit = impl_->tree.first_intersection(ray, skipped);
  if (!hit) return std::nullopt;
  RayHit result;
  result.triangle = static_cast<int>(hit->second - impl_->cgal_triangles.cbegin());
  if (const CgalPoint* p = boost::get<CgalPoint>(&hit->first)) {
    result.point = to_eigen(*p);
  } else if (const Kernel::Segment_3* s = boost::get<Kernel::Segment_3>(&hit->first)) {
    // The ray runs in the triangle's plane: the segment's end nearer the origin is the first contact.
    const Eigen::Vector3d a = to_eigen(s->source()), b = to_eigen(s->target());
    result.point = (a - origin).dot(unit) <= (b - origin).dot(unit) ? a : b;
  } else {
    return std::nullopt;
  }
  result.distance = (result.point - origin).dot(unit);
  return result;
}

}  // namespace needlekit::geometry
