// Helpers shared by the FE verification tests: rigid indenters placed in the tissue frame.
#pragma once
#include <Eigen/Core>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

namespace needlekit::fem::testing {

// Axis-aligned box [lo, hi] as a closed outward triangle mesh.
inline geometry::TriangleMesh box_surface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  geometry::TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// A needle of needlekit's own geometry pointing down (-z) with its tip at (x, y, z_tip): the needle frame (tip at
// z = L, base at z = 0) rotated by 180 degrees about x.
inline geometry::TriangleMesh placed_needle(const needle::NeedleGeometry& g, double x, double y, double z_tip,
                                            int segments = 64) {
  auto m = needle::needle_surface_mesh(g, {segments, 8});
  for (auto& v : m.vertices) v = Eigen::Vector3d(v.x() + x, -v.y() + y, g.length - v.z() + z_tip);
  return m;  // a proper rotation keeps the outward orientation
}

inline needle::NeedleGeometry flat_cylinder(double radius, double length) {
  needle::NeedleGeometry g;
  g.shape = needle::Shape::Cylinder;
  g.tip_diameter = g.base_diameter = 2 * radius;
  g.length = length;
  return g;
}

}  // namespace needlekit::fem::testing
