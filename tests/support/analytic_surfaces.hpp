// Triangle meshes of analytic surfaces for the geometry tests: cube, icosphere, open cylinder, flat grid. All are
// outward-oriented (counter-clockwise seen from outside) and consistently oriented.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::test {

// The cube [0, a]³ shifted by `origin`.
inline geometry::TriangleMesh cube_mesh(double a = 1.0, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) {
  geometry::TriangleMesh mesh;
  for (int k = 0; k < 8; ++k) mesh.vertices.push_back(origin + a * Eigen::Vector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1));
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

// The counter-clockwise quad a, b, c, d as two triangles, split along a-c or b-d.
inline void add_quad(geometry::TriangleMesh& mesh, int a, int b, int c, int d, bool split_ac) {
  if (split_ac) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  } else {
    mesh.triangles.push_back({a, b, d});
    mesh.triangles.push_back({b, c, d});
  }
}

// An icosahedron subdivided `levels` times (each triangle into four), vertices on the sphere of `radius` about
// `center`.
inline geometry::TriangleMesh icosphere_mesh(double radius, int levels,
                                             const Eigen::Vector3d& center = Eigen::Vector3d::Zero()) {
  const double p = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                                    {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  for (auto& x : v) x.normalize();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> g;
    for (const auto& t : f) {
      const int a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      g.push_back({t[0], a, c});
      g.push_back({t[1], b, a});
      g.push_back({t[2], c, b});
      g.push_back({a, b, c});
    }
    f = std::move(g);
  }
  geometry::TriangleMesh mesh;
  for (const auto& x : v) mesh.vertices.push_back(center + radius * x);
  mesh.triangles = f;
  return mesh;
}

// The open cylinder x² + y² = R², 0 ≤ z ≤ height, with `around` vertices per ring and `along` rows of quads, each
// quad split along alternating diagonals; normals point away from the axis.
inline geometry::TriangleMesh open_cylinder_mesh(double radius, double height, int around, int along) {
  geometry::TriangleMesh mesh;
  for (int j = 0; j <= along; ++j) {
    for (int i = 0; i < around; ++i) {
      const double phi = 2 * std::numbers::pi * i / around;
      mesh.vertices.emplace_back(radius * std::cos(phi), radius * std::sin(phi), height * j / along);
    }
  }
  const auto id = [&](int i, int j) { return j * around + (i % around); };
  for (int j = 0; j < along; ++j) {
    for (int i = 0; i < around; ++i) {
      add_quad(mesh, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
    }
  }
  return mesh;
}

// The square [-half, half]² in the plane z = 0 with n × n cells, each split along alternating diagonals; normals +z.
inline geometry::TriangleMesh plane_grid_mesh(double half, int n) {
  geometry::TriangleMesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) mesh.vertices.emplace_back(-half + 2 * half * i / n, -half + 2 * half * j / n, 0);
  }
  const auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      add_quad(mesh, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
    }
  }
  return mesh;
}

}  // namespace needlekit::test
