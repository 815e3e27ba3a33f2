// Helpers shared by the FE verification tests: rigid indenters placed in the tissue frame.
#pragma once
#include <Eigen/Core>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

namespace needlekit::fem::test_support {

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

}  // namespace needlekit::fem::test_support

#include <cmath>

#include "needlekit/mesh/structured_block_mesh.hpp"

namespace needlekit::fem::test_support {

// A quarter of a cube block of side 2 * extent (x, y in [0, extent] after the shift below is NOT applied: the block
// spans [-extent/2, extent/2]^2 x [-extent, 0] and the punch axis is the corner x = y = -extent/2), with a uniform
// round core of `core` cells over the punch radius `a`, graded outside with ratio about 1.3 per cell.
inline mesh::TetMesh quarter_punch_block(double a, double extent, int core, double youngs, double nu) {
  mesh::StructuredBlockOptions o;
  o.width = o.length = o.height = extent;
  o.core_cells = core;
  o.core_half_width = a;
  o.round_core = true;
  o.focus = {-extent / 2, -extent / 2};
  const int out = static_cast<int>(std::ceil(std::log(1 + (extent - a) / (a / core) * 0.3) / std::log(1.3)));
  o.nx = o.ny = o.nz = core + out;
  o.material = {"gel", 0, youngs, nu};
  return mesh::structured_block_mesh(o);
}

// Sneddon's flat cylindrical punch on a half-space: F = 2 a E delta / (1 - nu^2).
inline double sneddon_flat_punch_force(double a, double youngs, double nu, double depth) {
  return 2 * a * youngs * depth / (1 - nu * nu);
}

}  // namespace needlekit::fem::test_support

namespace needlekit::fem::test_support {

// A closed cone pointing down: apex at (x, y, 0), half-angle `half_angle` (rad), height `height`, base cap on top.
inline geometry::TriangleMesh cone_surface(double x, double y, double half_angle, double height, int segments = 128) {
  geometry::TriangleMesh m;
  const double r = height * std::tan(half_angle);
  m.vertices.emplace_back(x, y, 0.0);          // 0: apex
  m.vertices.emplace_back(x, y, height);       // 1: base centre
  for (int k = 0; k < segments; ++k) {
    const double t = 2 * M_PI * k / segments;
    m.vertices.emplace_back(x + r * std::cos(t), y + r * std::sin(t), height);
  }
  for (int k = 0; k < segments; ++k) {
    const int a = 2 + k, b = 2 + (k + 1) % segments;
    m.triangles.push_back({0, b, a});  // side, outward
    m.triangles.push_back({1, a, b});  // base cap, facing +z
  }
  if (geometry::signed_volume(m) < 0)
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// Sneddon's rigid cone on a half-space: contact radius c = (2/pi) tan(half_angle) delta and
// F = (2/pi) E / (1 - nu^2) tan(half_angle) delta^2 (= (2/pi) E* cot(alpha) delta^2 with alpha = 90 deg - half
// angle, the angle between the cone's face and the surface).
inline double sneddon_cone_force(double half_angle, double youngs, double nu, double depth) {
  return 2 / M_PI * youngs / (1 - nu * nu) * std::tan(half_angle) * depth * depth;
}

}  // namespace needlekit::fem::test_support
