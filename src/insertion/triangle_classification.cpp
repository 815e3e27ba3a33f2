#include "needlekit/insertion/triangle_classification.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/insertion/triangle_classification_parameters.hpp"

namespace needlekit::insertion {
namespace {

Eigen::Vector3d unnormalized_normal(const geometry::TriangleMesh& mesh, int t) {
  const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
  const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(tri[0])];
  return (mesh.vertices[static_cast<std::size_t>(tri[1])] - a).cross(mesh.vertices[static_cast<std::size_t>(tri[2])] - a);
}

double bounding_diagonal(const geometry::TriangleMesh& mesh) {
  Eigen::Vector3d lo = mesh.vertices.front(), hi = mesh.vertices.front();
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

// True when a ray from `origin` along `direction` hits the needle at a distance > `skip` (hits closer than that are
// the triangle the ray starts on or its neighbours).
bool ray_hits_needle(const geometry::SurfaceMesh& surface, const Eigen::Vector3d& origin,
                     const Eigen::Vector3d& direction, double skip) {
  const auto hit = surface.first_hit(origin + skip * direction, direction);
  return hit.has_value();
}

}  // namespace

std::string_view to_string(TriangleClass triangle_class) { return name_of(kTriangleClassNames, triangle_class); }

void validate_needle_surface(const geometry::TriangleMesh& needle, std::string_view what) {
  if (needle.vertices.empty() || needle.triangles.empty())
    throw InvalidInput(fmt::format("{}: the mesh is empty, expected a closed triangle surface of the needle", what));
  const int n = static_cast<int>(needle.vertices.size());
  for (std::size_t t = 0; t < needle.triangles.size(); ++t)
    for (int v : needle.triangles[t])
      if (v < 0 || v >= n)
        throw InvalidInput(fmt::format("{}: triangle {} refers to vertex {}, expected an index in [0, {})", what, t,
                                       v, n));
  const geometry::MeshTopologyReport topology = geometry::topology_report(needle);
  if (topology.non_manifold_edges > 0)
    throw InvalidInput(fmt::format("{}: {} non-manifold edges (used by more than two triangles), expected a closed "
                                   "manifold surface",
                                   what, topology.non_manifold_edges));
  if (topology.boundary_edges > 0)
    throw InvalidInput(fmt::format("{}: the surface is open ({} boundary edges), expected a closed surface", what,
                                   topology.boundary_edges));
  if (!topology.consistently_oriented)
    throw InvalidInput(fmt::format("{}: the triangles are not consistently oriented (a shared edge is used twice in "
                                   "the same direction), expected outward-oriented triangles",
                                   what));
  const double volume = geometry::signed_volume(needle);
  if (!(volume > 0))
    throw InvalidInput(fmt::format("{}: inverted normals: the enclosed volume is {:.6g} m^3 (negative), so the "
                                   "triangles' normals point inward; expected counter-clockwise triangles seen from "
                                   "outside (reverse the vertex order of every triangle)",
                                   what, volume));
}

namespace {

void validate(const TriangleClassificationOptions& options, const geometry::SurfaceMesh* surface) {
  const double d_norm = options.insertion_direction.norm();
  if (!(d_norm > 0) || !std::isfinite(d_norm))
    throw InvalidInput("insertion_direction: expected a finite, non-zero vector");
  check_ranges(kTriangleClassificationParameters, options, "classification");
  if (options.occlusion_test && surface == nullptr)
    throw InvalidInput("occlusion_test: the occlusion test casts rays against the needle and needs its SurfaceMesh");
}

// The class of one non-degenerate triangle with unit normal n: by the angle of n to d (§3.6.1), then a channel (an
// inward-facing triangle inside the bore radius, or not visible from outside) or occluded (jagged needles: a ray
// from each vertex along d hits the needle).
TriangleClass class_of(const geometry::TriangleMesh& needle, std::size_t t, const Eigen::Vector3d& n,
                       const Eigen::Vector3d& d, const TriangleClassificationOptions& options,
                       const geometry::SurfaceMesh* surface, double skip) {
  const double cos_angle = n.dot(d);
  TriangleClass cls;
  if (std::abs(cos_angle) <= std::sin(options.side_tolerance)) cls = TriangleClass::Side;  // within tolerance of π/2
  else if (cos_angle < 0) cls = TriangleClass::Back;
  else cls = cos_angle >= std::cos(options.alpha_tolerance) ? TriangleClass::Alpha : TriangleClass::Beta;

  const auto& tri = needle.triangles[t];
  const Eigen::Vector3d centroid =
      (needle.vertices[static_cast<std::size_t>(tri[0])] + needle.vertices[static_cast<std::size_t>(tri[1])] +
       needle.vertices[static_cast<std::size_t>(tri[2])]) / 3.0;
  Eigen::Vector3d radial = centroid - options.axis_point;
  radial -= radial.dot(d) * d;
  const double rho = radial.norm();
  const bool faces_axis = rho > 0 && n.dot(radial) < -1e-12 * rho;
  if (faces_axis && cls != TriangleClass::Back) {
    bool channel = options.bore_radius > 0 && rho <= options.bore_radius * (1 + 1e-6);
    if (!channel && surface != nullptr && cls != TriangleClass::Side)
      channel = ray_hits_needle(*surface, centroid, n, skip);
    if (channel) cls = TriangleClass::Channel;
  }
  if (options.occlusion_test && (cls == TriangleClass::Alpha || cls == TriangleClass::Beta)) {
    bool all_hit = true;
    for (int corner = 0; corner < 3 && all_hit; ++corner) {
      const Eigen::Vector3d& v = needle.vertices[static_cast<std::size_t>(tri[corner])];
      // Start a hair inside the triangle, so that the neighbours sharing the vertex are not hit.
      const Eigen::Vector3d origin = v + 1e-6 * (centroid - v);
      all_hit = ray_hits_needle(*surface, origin, d, skip);
    }
    if (all_hit) cls = TriangleClass::Occluded;
  }
  return cls;
}

void count(TriangleClassification& result, int t, TriangleClass cls, double area) {
  result.classes[static_cast<std::size_t>(t)] = cls;
  switch (cls) {
    case TriangleClass::Alpha:
      result.alpha.push_back(t);
      result.alpha_area += area;
      break;
    case TriangleClass::Beta:
      result.beta.push_back(t);
      result.beta_area += area;
      break;
    case TriangleClass::Side: ++result.side; break;
    case TriangleClass::Back: ++result.back; break;
    case TriangleClass::Channel: ++result.channel; break;
    case TriangleClass::Occluded: ++result.occluded; break;
  }
}

}  // namespace

TriangleClassification classify_triangles(const geometry::TriangleMesh& needle,
                                          const TriangleClassificationOptions& options,
                                          const geometry::SurfaceMesh* surface) {
  validate(options, surface);
  validate_needle_surface(needle);
  TriangleClassification result;
  const Eigen::Vector3d d = options.insertion_direction / options.insertion_direction.norm();
  result.insertion_direction = d;
  const double skip = 1e-9 * bounding_diagonal(needle);  // rays start this far off the surface
  const std::size_t triangles = needle.triangles.size();
  result.classes.resize(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const Eigen::Vector3d normal_area = unnormalized_normal(needle, static_cast<int>(t));
    const double twice_area = normal_area.norm();
    if (!(twice_area > 0)) {  // degenerate: no direction, no area, no load
      count(result, static_cast<int>(t), TriangleClass::Side, 0);
      continue;
    }
    count(result, static_cast<int>(t),
          class_of(needle, t, normal_area / twice_area, d, options, surface, skip), 0.5 * twice_area);
  }
  if (result.alpha.empty() && result.beta.empty())
    throw InvalidInput(fmt::format("needle mesh: no triangle faces the insertion direction ({:.6g}, {:.6g}, {:.6g}) "
                                   "({} side, {} back, {} channel, {} occluded triangles); expected a tip whose "
                                   "outward normals point along the insertion direction (is the needle pointing the "
                                   "other way?)",
                                   d.x(), d.y(), d.z(), result.side, result.back, result.channel, result.occluded));
  return result;
}

}  // namespace needlekit::insertion
