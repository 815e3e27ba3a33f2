#include "needlekit/needle/needle_surface_mesh.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>
#include <vector>

#include "needlekit/core/errors.hpp"

// The mesh is the boundary of an exact polyhedron: the prism over a polygon inscribed in the outer circle (for a cone,
// the frustum over it), minus the prism over a polygon inscribed in the bore circle, cut by the bevel plane. Its
// volume therefore differs from volume(needle) only by the inscribed-polygon error, O(1/n²) for n circumferential
// segments. Every wall facet between two neighbouring columns is planar (both columns are straight generators), so
// the wall vertices at the axial levels never change the volume, and the columns that the bevel plane cuts end
// exactly on the plane, where the bevel face reuses them: no T-junctions.

namespace needlekit::needle {
namespace {

using Triangle = std::array<int, 3>;

// Relative tolerance below which a chord is taken as tangent to a circle (a bore just touching the tip chord, a
// bevel with D1 = D2): treating the near-tangent case as tangent moves the geometry by at most this fraction of the
// radius and avoids slivers.
constexpr double kTangentTolerance = 1e-9;

// ---- triangulation of a planar polygon with at most one hole ---------------------------------------------------
// Hand-written on purpose: the planar faces here are simple polygons with at most one hole and at most a few
// thousand vertices, for which ear clipping after bridging the hole (D. Eberly, "Triangulation by Ear Clipping",
// Geometric Tools, 2002) is exact and fast enough; the Debian alternative (CGAL's constrained triangulation) would
// dominate the build time of the whole library.

struct PolygonVertex {
  Eigen::Vector2d p;
  int id = 0;  // mesh vertex index
};
using Polygon = std::vector<PolygonVertex>;

// Twice the signed area of the triangle abc: positive when a, b, c turn counter-clockwise.
double orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// p inside or on the triangle abc, whatever its orientation.
bool in_closed_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Vector2d& c) {
  const double d1 = orientation(a, b, p), d2 = orientation(b, c, p), d3 = orientation(c, a, p);
  const bool negative = d1 < 0 || d2 < 0 || d3 < 0, positive = d1 > 0 || d2 > 0 || d3 > 0;
  return !(negative && positive);
}

[[noreturn]] void triangulation_failed(const char* step) {
  throw std::logic_error(fmt::format("needle_surface_mesh: {} failed on a face polygon (internal error)", step));
}

// Joins a clockwise hole to a counter-clockwise outer boundary by a two-way bridge from the hole's rightmost vertex M
// to an outer vertex visible from it (Eberly §3), giving one weakly simple counter-clockwise polygon.
Polygon bridge_hole(const Polygon& outer, const Polygon& hole) {
  const std::size_t n = outer.size(), h = hole.size();
  const std::size_t m = static_cast<std::size_t>(
      std::max_element(hole.begin(), hole.end(), [](const auto& a, const auto& b) { return a.p.x() < b.p.x(); }) -
      hole.begin());
  const Eigen::Vector2d M = hole[m].p;

  // Nearest crossing I of the ray M + t·(1, 0), t >= 0, with an outer edge; P is that edge's end with the larger x.
  double crossing_x = std::numeric_limits<double>::infinity();
  std::size_t p = n;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = outer[i].p;
    const Eigen::Vector2d& b = outer[(i + 1) % n].p;
    if ((a.y() > M.y()) == (b.y() > M.y())) continue;
    const double x = a.x() + (M.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
    if (x >= M.x() && x < crossing_x) {
      crossing_x = x;
      p = a.x() > b.x() ? i : (i + 1) % n;
    }
  }
  if (p == n) triangulation_failed("bridging a hole");

  // A reflex outer vertex inside the triangle M I P hides P; then bridge to the hidden vertex closest in angle to the
  // ray instead.
  const Eigen::Vector2d I(crossing_x, M.y());
  const Eigen::Vector2d P = outer[p].p;
  if (orientation(M, I, P) != 0) {
    double best_slope = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d& v = outer[k].p;
      const bool reflex = orientation(outer[(k + n - 1) % n].p, v, outer[(k + 1) % n].p) < 0;
      if (k == p || !reflex || !in_closed_triangle(v, M, I, P)) continue;
      const double slope = std::abs(v.y() - M.y()) / (v.x() - M.x());  // tan of the angle to the ray
      if (slope < best_slope) {
        best_slope = slope;
        p = k;
      }
    }
  }

  Polygon merged(outer.begin(), outer.begin() + static_cast<std::ptrdiff_t>(p) + 1);
  for (std::size_t k = 0; k <= h; ++k) merged.push_back(hole[(m + k) % h]);  // around the hole, back to M
  merged.push_back(outer[p]);
  merged.insert(merged.end(), outer.begin() + static_cast<std::ptrdiff_t>(p) + 1, outer.end());
  return merged;
}

// Ear clipping of a (weakly) simple counter-clockwise polygon; the triangles are counter-clockwise.
std::vector<Triangle> ear_clipping(const Polygon& polygon) {
  const int n = static_cast<int>(polygon.size());
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto is_ear = [&](int u, int v, int w) {
    const Eigen::Vector2d &a = polygon[u].p, &b = polygon[v].p, &c = polygon[w].p;
    if (orientation(a, b, c) <= 0) return false;
    for (int k = next[w]; k != u; k = next[k]) {
      const int id = polygon[k].id;  // bridge copies of a corner share its id and are not obstacles
      if (id == polygon[u].id || id == polygon[v].id || id == polygon[w].id) continue;
      if (in_closed_triangle(polygon[k].p, a, b, c)) return false;
    }
    return true;
  };

  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(std::max(n - 2, 0)));
  int remaining = n, v = 0, misses = 0;
  while (remaining > 3) {
    const int u = prev[v], w = next[v];
    if (is_ear(u, v, w)) {
      triangles.push_back({polygon[u].id, polygon[v].id, polygon[w].id});
      next[u] = w;
      prev[w] = u;
      --remaining;
      misses = 0;
      v = next[w];  // skip one vertex: ears spread over the polygon instead of fanning out of one vertex
    } else {
      v = w;
      if (++misses > remaining) triangulation_failed("ear clipping");
    }
  }
  if (orientation(polygon[prev[v]].p, polygon[v].p, polygon[next[v]].p) <= 0) triangulation_failed("ear clipping");
  triangles.push_back({polygon[prev[v]].id, polygon[v].id, polygon[next[v]].id});
  return triangles;
}

// ---- the needle's rims ---------------------------------------------------------------------------------------------

// How the bevel plane cuts the columns on one circle (outer wall or bore).
enum class Cut {
  None,  // no column is cut: all reach the tip face
  All,   // every column ends on the bevel plane
  Arc,   // nodes 0 ..= arc_end (the arc x >= x_chord) end on the plane; nodes 0 and arc_end lie on the tip chord
};

// The nodes of one circle, counter-clockwise, each the foot of a vertical column of mesh vertices.
struct Rim {
  std::vector<Eigen::Vector2d> xy;  // at z = 0
  std::vector<double> top;          // height of each column
  Cut cut = Cut::None;
  int arc_end = 0;
};

// n nodes at angles start + k·2π/n.
std::vector<Eigen::Vector2d> uniform_nodes(double radius, int n, double start) {
  std::vector<Eigen::Vector2d> xy;
  for (int k = 0; k < n; ++k) {
    const double angle = start + 2 * M_PI * k / n;
    xy.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  return xy;
}

// n nodes with the two crossings (x_chord, ±y) of the chord x = x_chord as nodes 0 and arc_end, spread uniformly
// over the arc x >= x_chord (arc_end segments, at least 2) and over the rest (at least 2). The crossings are placed
// exactly on the chord so that the tip face and the bevel face share straight edges.
Rim chord_split_rim(double radius, double x_chord, int n) {
  const double half_arc = std::acos(x_chord / radius);
  Rim rim;
  rim.cut = Cut::Arc;
  rim.arc_end = std::clamp(static_cast<int>(std::lround(n * half_arc / M_PI)), 2, n - 2);
  const double y = std::sqrt(std::max(0.0, radius * radius - x_chord * x_chord));
  for (int k = 0; k < n; ++k) {
    if (k == 0 || k == rim.arc_end) {
      rim.xy.emplace_back(x_chord, k == 0 ? -y : y);
      continue;
    }
    const double angle = k < rim.arc_end ? -half_arc + 2 * half_arc * k / rim.arc_end
                                         : half_arc + (2 * M_PI - 2 * half_arc) * (k - rim.arc_end) / (n - rim.arc_end);
    rim.xy.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  return rim;
}

// Largest angle between neighbouring nodes.
double largest_step(const Rim& rim) {
  double step = 0;
  for (std::size_t k = 0; k < rim.xy.size(); ++k) {
    const Eigen::Vector2d& a = rim.xy[k];
    const Eigen::Vector2d& b = rim.xy[(k + 1) % rim.xy.size()];
    step = std::max(step, std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)));
  }
  return step;
}

// ---- assembling the mesh ---------------------------------------------------------------------------------------

class MeshBuilder {
public:
  int add_vertex(const Eigen::Vector3d& p) {
    mesh_.vertices.push_back(p);
    return static_cast<int>(mesh_.vertices.size()) - 1;
  }

  // Vertex columns of a rim, bottom to top: z = 0, the axial levels below the top, the top. Levels closer than a
  // quarter level to the top are left out (no slivers); the facets are planar, so this does not move the surface.
  // `radius_scale(z)` scales the base-radius nodes (a cone narrows towards the tip).
  template <class RadiusScale>
  std::vector<std::vector<int>> add_columns(const Rim& rim, double length, int levels, RadiusScale radius_scale) {
    const double dz = length / levels;
    std::vector<std::vector<int>> columns;
    for (std::size_t k = 0; k < rim.xy.size(); ++k) {
      auto vertex_at = [&](double z) {
        const Eigen::Vector2d xy = rim.xy[k] * radius_scale(z);
        return add_vertex({xy.x(), xy.y(), z});
      };
      std::vector<int> column{vertex_at(0.0)};
      for (int i = 1; i < levels && i * dz < rim.top[k] - 0.25 * dz; ++i) column.push_back(vertex_at(i * dz));
      if (rim.top[k] > 0) column.push_back(vertex_at(rim.top[k]));
      columns.push_back(std::move(column));
    }
    return columns;
  }

  // The wall between each pair of neighbouring columns (cyclically), zipped by height so that every vertex of both
  // columns is used. Counter-clockwise columns give outward normals; `outward = false` (the bore) flips them.
  void add_wall(const std::vector<std::vector<int>>& columns, bool outward) {
    for (std::size_t j = 0; j < columns.size(); ++j) {
      const std::vector<int>& left = columns[j];
      const std::vector<int>& right = columns[(j + 1) % columns.size()];
      std::size_t i = 0, k = 0;
      while (i + 1 < left.size() || k + 1 < right.size()) {
        const bool advance_left =
            k + 1 == right.size() ||
            (i + 1 < left.size() && mesh_.vertices[left[i + 1]].z() <= mesh_.vertices[right[k + 1]].z());
        if (advance_left) {
          add_triangle({left[i], right[k], left[i + 1]}, outward);
          ++i;
        } else {
          add_triangle({left[i], right[k], right[k + 1]}, outward);
          ++k;
        }
      }
    }
  }

  // A planar face from its boundary (counter-clockwise in the xy projection) and an optional hole (any orientation),
  // triangulated in the xy projection; `upward` faces have normals with positive z, the base has `upward = false`.
  void add_planar_face(const std::vector<int>& boundary, std::vector<int> hole, bool upward) {
    auto polygon = [&](const std::vector<int>& ids) {
      Polygon result;
      for (int id : ids) result.push_back({mesh_.vertices[id].head<2>(), id});
      return result;
    };
    Polygon face = polygon(boundary);
    if (!hole.empty()) {
      Polygon inner = polygon(hole);
      double twice_area = 0;
      for (std::size_t k = 0; k < inner.size(); ++k) {
        twice_area += orientation(Eigen::Vector2d::Zero(), inner[k].p, inner[(k + 1) % inner.size()].p);
      }
      if (twice_area > 0) std::reverse(inner.begin(), inner.end());  // bridging needs a clockwise hole
      face = bridge_hole(face, inner);
    }
    for (const Triangle& t : ear_clipping(face)) add_triangle(t, upward);
  }

  geometry::TriangleMesh take() { return std::move(mesh_); }

private:
  void add_triangle(const Triangle& t, bool keep_orientation) {
    mesh_.triangles.push_back(keep_orientation ? t : Triangle{t[0], t[2], t[1]});
  }

  geometry::TriangleMesh mesh_;
};

std::vector<int> tops(const std::vector<std::vector<int>>& columns) {
  std::vector<int> ids;
  for (const auto& column : columns) ids.push_back(column.back());
  return ids;
}
std::vector<int> bottoms(const std::vector<std::vector<int>>& columns) {
  std::vector<int> ids;
  for (const auto& column : columns) ids.push_back(column.front());
  return ids;
}

void check_options(const NeedleMeshOptions& options) {
  if (options.circumferential_segments < 8) {
    throw InvalidInput(fmt::format("needle mesh: circumferential_segments = {}, expected an integer >= 8",
                                   options.circumferential_segments));
  }
  if (options.axial_segments < 1) {
    throw InvalidInput(
        fmt::format("needle mesh: axial_segments = {}, expected an integer >= 1", options.axial_segments));
  }
}

// The rims of the needle's cross-section (outside and bore) with the height of every column's top: on the bevel
// plane where it cuts the column, otherwise at the tip.
struct Rims {
  bool bevel = false;  // a bevel with D1 < D2 (a bevel with D1 = D2 is the cylinder: its plane only touches the rim)
  Rim outer, inner;
};

Rims rims_of(const NeedleGeometry& needle, int n) {
  const double length = needle.length;
  const double r = needle.base_diameter / 2, bore = needle.bore_diameter / 2;
  const double c = needle.base_diameter - needle.tip_diameter;
  Rims rims;
  rims.bevel = needle.shape == Shape::Bevel && c > kTangentTolerance * r;
  // Tip chord: the bevel keeps x <= x_cut(s) = r − c + c·s/L; at the tip (s = 0) that is x_t = r − c = D1 − r.
  const double x_chord = r - c;
  // Height of the bevel plane above the point x: z = L − s with x = x_cut(s), i.e. z = (r − x)·L/c, in [0, L].
  auto plane_height = [&](double x) { return std::clamp((r - x) * length / c, 0.0, length); };
  auto set_tops = [&](Rim& rim) {
    for (int k = 0; k < n; ++k) {
      const bool cut = rim.cut == Cut::All || (rim.cut == Cut::Arc && 0 < k && k < rim.arc_end);
      rim.top.push_back(cut ? plane_height(rim.xy[k].x()) : length);
    }
  };
  Rim& outer = rims.outer;
  if (rims.bevel) outer = chord_split_rim(r, x_chord, n);
  else outer.xy = uniform_nodes(r, n, 0.0);
  set_tops(outer);
  if (!needle.hollow()) return rims;
  Rim& inner = rims.inner;
  if (!rims.bevel) {
    inner.xy = uniform_nodes(bore, n, 0.0);  // aligned with the outer nodes: the bore polygon is a scaled copy
  } else if (std::abs(x_chord) < bore * (1 - kTangentTolerance)) {
    inner = chord_split_rim(bore, x_chord, n);  // the tip chord cuts the bore
  } else {
    // The bore opens entirely in the tip face (x_t >= D3/2) or in the bevel face (x_t <= −D3/2). The nodes are
    // offset by half a step from the point where the chord could touch the bore, so no node lies on the chord.
    inner.cut = x_chord > 0 ? Cut::None : Cut::All;
    inner.xy = uniform_nodes(bore, n, (x_chord > 0 ? 0.0 : M_PI) + M_PI / n);
  }
  set_tops(inner);
  // A bevel's bore nodes are not aligned with the outer ones, so the bore polygon must stay inside the outer
  // polygon, whose inscribed circle has the radius r·cos(largest step / 2).
  if (rims.bevel && bore >= r * std::cos(largest_step(outer) / 2)) {
    throw InvalidInput(fmt::format(
        "needle mesh: circumferential_segments = {} is too coarse for the wall between the bore ({:.6g} um) and the "
        "outside ({:.6g} um); use more segments",
        n, needle.bore_diameter * 1e6, needle.base_diameter * 1e6));
  }
  return rims;
}

// Tip face (x <= x_t) and bevel face (x >= x_t), both counter-clockwise seen from +z. The outer arc 0 ..= arc_end
// is the bevel's; the tip face runs over the rest and closes along the chord.
void add_bevel_faces(const Rims& rims, const std::vector<int>& outer_top, const std::vector<int>& inner_top, int n,
                     MeshBuilder& builder) {
  const int outer_end = rims.outer.arc_end;
  std::vector<int> tip(outer_top.begin() + outer_end, outer_top.end());
  tip.push_back(outer_top.front());
  std::vector<int> bevel_face(outer_top.begin(), outer_top.begin() + outer_end + 1);
  std::vector<int> tip_hole, bevel_hole;
  switch (rims.inner.cut) {
    case Cut::None: tip_hole = inner_top; break;
    case Cut::All: bevel_hole = inner_top; break;
    case Cut::Arc: {
      // The chord runs from the outer rim into the bore and out again; each face follows the bore arc on its side,
      // clockwise (the bore is a hole in both).
      const int inner_end = rims.inner.arc_end;
      tip.push_back(inner_top.front());
      for (int k = n - 1; k >= inner_end; --k) tip.push_back(inner_top[k]);
      for (int k = inner_end; k >= 0; --k) bevel_face.push_back(inner_top[k]);
      break;
    }
  }
  builder.add_planar_face(tip, tip_hole, true);
  builder.add_planar_face(bevel_face, bevel_hole, true);
}

}  // namespace

geometry::TriangleMesh needle_surface_mesh(const NeedleGeometry& needle, const NeedleMeshOptions& options) {
  validate(needle);
  check_options(options);
  const int n = options.circumferential_segments;
  const double length = needle.length;
  const Rims rims = rims_of(needle, n);
  MeshBuilder builder;
  // Cone: the radius goes linearly from r at the base to D1/2 at the tip; the nodes are scaled (Table 4.2 frustum).
  const double tip_scale = needle.shape == Shape::Cone ? needle.tip_diameter / needle.base_diameter : 1.0;
  auto outer_scale = [&](double z) { return 1 + (tip_scale - 1) * z / length; };
  auto constant_scale = [](double) { return 1.0; };
  const auto outer_columns = builder.add_columns(rims.outer, length, options.axial_segments, outer_scale);
  builder.add_wall(outer_columns, true);
  std::vector<std::vector<int>> inner_columns;
  if (needle.hollow()) {
    inner_columns = builder.add_columns(rims.inner, length, options.axial_segments, constant_scale);
    builder.add_wall(inner_columns, false);
  }
  // Base: the full disk (annulus), facing −z.
  builder.add_planar_face(bottoms(outer_columns), bottoms(inner_columns), false);
  if (rims.bevel) {
    add_bevel_faces(rims, tops(outer_columns), tops(inner_columns), n, builder);
  } else {
    builder.add_planar_face(tops(outer_columns), tops(inner_columns), true);  // tip disk (annulus)
  }
  return builder.take();
}

}  // namespace needlekit::needle
