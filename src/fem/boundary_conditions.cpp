#include "boundary_conditions.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/tet_adjacency.hpp"
#include "tet_kernel.hpp"

namespace needlekit::fem::detail {
namespace {
// The linear triangles of one top face (`face`: its three corners, then for a quadratic face its three mid-edge
// nodes in any order), counter-clockwise seen from above: the face itself, or its four corner/mid-edge sub-triangles.
void add_top_triangles(const std::vector<Eigen::Vector3d>& nodes, const std::vector<int>& face,
                       std::vector<std::array<int, 3>>& out) {
  std::array<int, 3> c{face[0], face[1], face[2]};
  const Eigen::Vector3d up = (nodes[c[1]] - nodes[c[0]]).cross(nodes[c[2]] - nodes[c[0]]);
  if (up.z() < 0) std::swap(c[1], c[2]);
  if (face.size() == 3) {
    out.push_back(c);
    return;
  }
  std::array<int, 3> mid{};  // mid[k]: the node on the edge (c[k], c[k+1])
  for (size_t m = 3; m < face.size(); ++m) {
    int best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double distance = (nodes[face[m]] - 0.5 * (nodes[c[k]] + nodes[c[(k + 1) % 3]])).norm();
      if (distance < best_distance) best_distance = distance, best = k;
    }
    mid[best] = face[m];
  }
  out.push_back({c[0], mid[0], mid[2]});
  out.push_back({mid[0], c[1], mid[1]});
  out.push_back({mid[2], mid[1], c[2]});
  out.push_back({mid[0], mid[1], mid[2]});
}
}  // namespace

TopSurface top_surface(const mesh::TetMesh& mesh, const FunctionSpace& space, double tol) {
  const int nnode = static_cast<int>(space.nodes.size());
  const int nn = space.nodes_per_element;
  TopSurface top;
  top.z = space.box_max.z();
  top.node_area.assign(static_cast<size_t>(nnode), 0.0);
  top.node_size.assign(static_cast<size_t>(nnode), std::numeric_limits<double>::infinity());
  std::vector<char> is_top(static_cast<size_t>(nnode), 0);
  const mesh::BoundarySurface boundary = mesh::boundary_surface(mesh, mesh::tet_topology(mesh));
  for (size_t f = 0; f < boundary.triangles.size(); ++f) {
    const auto& k = boundary.triangles[f];
    if (std::abs(mesh.nodes[k[0]].z() - top.z) > tol || std::abs(mesh.nodes[k[1]].z() - top.z) > tol ||
        std::abs(mesh.nodes[k[2]].z() - top.z) > tol)
      continue;
    const double area = 0.5 * (mesh.nodes[k[1]] - mesh.nodes[k[0]]).cross(mesh.nodes[k[2]] - mesh.nodes[k[0]]).norm();
    const double h = std::sqrt(2 * area);
    const int e = boundary.tets[f];
    std::vector<int> face_nodes(k.begin(), k.end());
    if (nn == 10) {
      for (int c = 0; c < 3; ++c) top.node_area[k[c]] += area / 12;  // T6 face: corners A/12, mid-edges A/4
      for (int ed = 0; ed < 6; ++ed) {
        const int a = mesh.tets[e][tet_edges[ed][0]], b = mesh.tets[e][tet_edges[ed][1]];
        if (std::count(k.begin(), k.end(), a) && std::count(k.begin(), k.end(), b)) {
          const int mid = space.connectivity[static_cast<size_t>(e) * 10 + 4 + ed];
          top.node_area[mid] += area / 4;
          face_nodes.push_back(mid);
        }
      }
    } else {
      for (int c = 0; c < 3; ++c) top.node_area[k[c]] += area / 3;
    }
    add_top_triangles(space.nodes, face_nodes, top.triangles);
    for (int n : face_nodes) {
      is_top[n] = 1;
      top.node_size[n] = std::min(top.node_size[n], h);
    }
  }
  for (int n = 0; n < nnode; ++n)
    if (is_top[n]) top.nodes.push_back(n);
  if (top.nodes.empty()) {
    std::ostringstream s;
    s << "tissue mesh: no boundary faces on the top surface z = " << top.z << " m";
    throw InvalidInput(s.str());
  }
  return top;
}

std::vector<char> fixed_dofs(const FunctionSpace& space, BoundaryCondition condition, double tol) {
  const Eigen::Vector3d& lo = space.box_min;
  const Eigen::Vector3d& hi = space.box_max;
  std::vector<char> fixed(3 * space.nodes.size(), 0);
  for (size_t n = 0; n < space.nodes.size(); ++n) {
    const auto& p = space.nodes[n];
    char* f = &fixed[3 * n];
    const bool bottom = p.z() < lo.z() + tol;
    const bool side_x = p.x() < lo.x() + tol || p.x() > hi.x() - tol;
    const bool side_y = p.y() < lo.y() + tol || p.y() > hi.y() - tol;
    switch (condition) {
      case BoundaryCondition::SidesAndBottomFixed:
        if (bottom || side_x || side_y) f[0] = f[1] = f[2] = 1;
        break;
      case BoundaryCondition::BottomFixed:
        if (bottom) f[0] = f[1] = f[2] = 1;
        break;
      case BoundaryCondition::BottomFixedSidesRoller:
        if (bottom) f[0] = f[1] = f[2] = 1;
        if (side_x) f[0] = 1;
        if (side_y) f[1] = 1;
        break;
      case BoundaryCondition::SymmetryPlanes:
        if (p.x() < lo.x() + tol) f[0] = 1;
        if (p.y() < lo.y() + tol) f[1] = 1;
        if (bottom) f[2] = 1;
        break;
      case BoundaryCondition::QuarterSymmetry:
        if (p.x() < lo.x() + tol) f[0] = 1;
        if (p.y() < lo.y() + tol) f[1] = 1;
        if (bottom || p.x() > hi.x() - tol || p.y() > hi.y() - tol) f[0] = f[1] = f[2] = 1;
        break;
      case BoundaryCondition::HalfSymmetry:
        if (p.y() < lo.y() + tol) f[1] = 1;
        if (bottom || side_x || p.y() > hi.y() - tol) f[0] = f[1] = f[2] = 1;
        break;
    }
  }
  return fixed;
}

namespace {

// The flat tip face of a needle seen from below: its triangles in the (x, y) plane, and the circular segments
// between the face's boundary edges (the mesh's inscribed polygon) and the needle's true outline.
struct TipOutline {
  std::vector<std::array<Eigen::Vector2d, 3>> triangles;
  struct Segment {             // the part of the circle through the edge's ends outside the chord p-q
    Eigen::Vector2d p = Eigen::Vector2d::Zero(), q = Eigen::Vector2d::Zero(), centre = Eigen::Vector2d::Zero();
    Eigen::Vector2d outward = Eigen::Vector2d::Zero();  // normal of the chord, away from the face
    double radius = 0;
  };
  std::vector<Segment> segments;

  bool contains(const Eigen::Vector2d& x) const {
    for (const auto& t : triangles) {
      const Eigen::Vector2d e1 = t[1] - t[0], e2 = t[2] - t[0], w = x - t[0];
      const double det = e1.x() * e2.y() - e1.y() * e2.x();
      const double s = (w.x() * e2.y() - w.y() * e2.x()) / det, r = (e1.x() * w.y() - e1.y() * w.x()) / det;
      const double eps = 1e-7;
      if (s >= -eps && r >= -eps && s + r <= 1 + eps) return true;
    }
    for (const auto& g : segments) {
      const Eigen::Vector2d chord = g.q - g.p;
      const double along = (x - g.p).dot(chord) / chord.squaredNorm();
      if (along < 0 || along > 1 || (x - g.p).dot(g.outward) < 0) continue;
      if ((x - g.centre).norm() <= g.radius * (1 + 1e-9)) return true;  // on the outline counts as under the tip
    }
    return false;
  }
};

// Circle through three points in the plane; radius 0 when they are collinear.
std::pair<Eigen::Vector2d, double> circumcircle(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                                const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a, ac = c - a;
  const double det = 2 * (ab.x() * ac.y() - ab.y() * ac.x());
  if (!(std::abs(det) > 1e-9 * ab.norm() * ac.norm())) return {a, 0.0};  // collinear (or repeated) points
  const Eigen::Vector2d centre =
      a + Eigen::Vector2d(ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm(),
                          ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm()) / det;
  return {centre, (centre - a).norm()};
}

// The tip face: triangles at the needle's lowest level facing down (within `ntol` of it). Their boundary, ordered
// into loops, is the mesh's polygon of the outline; a curved outline (a cylinder's circle, a bevel's elliptical
// arc) has its vertices on the true curve, so each boundary edge gets the circular segment of the circle through it
// and its neighbour vertex (of the two neighbours, the larger circle: a straight run, such as a bevel face's chord,
// gives none). A node on the true outline is then under the tip (Eq 3.9's nodes on the tip's edge), not only the
// nodes inside the inscribed polygon.
TipOutline tip_outline(const geometry::TriangleMesh& needle, double ntol) {
  double zmin = std::numeric_limits<double>::infinity();
  for (const auto& v : needle.vertices) zmin = std::min(zmin, v.z());
  TipOutline outline;
  std::map<std::pair<int, int>, int> edge_count;  // undirected edge -> uses
  std::map<int, std::pair<int, int>> next;        // boundary vertex -> (next vertex, opposite vertex of its triangle)
  std::vector<std::array<int, 3>> tip;
  for (const auto& t : needle.triangles) {
    const auto &a = needle.vertices[t[0]], &b = needle.vertices[t[1]], &c = needle.vertices[t[2]];
    if (a.z() > zmin + ntol || b.z() > zmin + ntol || c.z() > zmin + ntol) continue;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() == 0 || n.normalized().z() > -0.999) continue;
    outline.triangles.push_back({a.head<2>(), b.head<2>(), c.head<2>()});
    tip.push_back(t);
    for (int k = 0; k < 3; ++k) edge_count[std::minmax(t[k], t[(k + 1) % 3])]++;
  }
  bool manifold = true;
  for (const auto& t : tip)
    for (int k = 0; k < 3; ++k)
      if (edge_count[std::minmax(t[k], t[(k + 1) % 3])] == 1)
        manifold = next.emplace(t[k], std::make_pair(t[(k + 1) % 3], t[(k + 2) % 3])).second && manifold;
  if (!manifold) return outline;  // a boundary vertex with two outgoing edges: keep the polygon alone
  std::map<int, int> previous;
  for (const auto& [from, to] : next) previous[to.first] = from;
  const auto xy = [&](int v) -> Eigen::Vector2d { return needle.vertices[v].head<2>(); };
  for (const auto& [p, to] : next) {
    const int q = to.first, opposite = to.second;
    const auto before = previous.find(p);
    const auto after = next.find(q);
    if (before == previous.end() || after == next.end()) continue;
    TipOutline::Segment best;
    for (const auto& [centre, radius] :
         {circumcircle(xy(before->second), xy(p), xy(q)), circumcircle(xy(p), xy(q), xy(after->second.first))}) {
      if (radius == 0) continue;
      // Convex there: the centre on the face's side of the chord (the side of the triangle's third vertex).
      const Eigen::Vector2d chord = xy(q) - xy(p);
      const auto side = [&](const Eigen::Vector2d& x) {
        const Eigen::Vector2d w = x - xy(p);
        return chord.x() * w.y() - chord.y() * w.x();
      };
      if (side(centre) * side(xy(opposite)) <= 0) continue;
      const Eigen::Vector2d normal = Eigen::Vector2d(chord.y(), -chord.x()) * (side(xy(opposite)) > 0 ? 1 : -1);
      if (best.radius == 0 || radius > best.radius) best = {xy(p), xy(q), centre, normal, radius};
    }
    if (best.radius > 0) outline.segments.push_back(best);
  }
  return outline;
}

}  // namespace

std::vector<int> tip_nodes(const TopSurface& top, const FunctionSpace& space, const geometry::TriangleMesh& needle,
                           double ntol) {
  const TipOutline outline = tip_outline(needle, ntol);
  std::vector<int> nodes;
  if (!outline.triangles.empty())
    for (int n : top.nodes)
      if (outline.contains(space.nodes[n].head<2>())) nodes.push_back(n);
  if (nodes.empty()) {  // sharp tip: the top node nearest to the apex
    double zmin = std::numeric_limits<double>::infinity();
    for (const auto& v : needle.vertices) zmin = std::min(zmin, v.z());
    Eigen::Vector2d apex = Eigen::Vector2d::Zero();
    for (const auto& v : needle.vertices)
      if (v.z() <= zmin + ntol) {
        apex = v.head<2>();
        break;
      }
    int best = top.nodes[0];
    for (int n : top.nodes)
      if ((space.nodes[n].head<2>() - apex).norm() < (space.nodes[best].head<2>() - apex).norm()) best = n;
    nodes.push_back(best);
  }
  return nodes;
}

DofMap dof_map(const std::vector<char>& fixed, const std::vector<std::vector<int>>& tip_nodes_per_needle,
               const std::vector<int>& node_order) {
  DofMap map;
  map.tip_dof.assign(fixed.size(), 0);
  for (const auto& nodes : tip_nodes_per_needle)
    for (int a : nodes)
      if (!fixed[3 * a + 2]) map.tip_dof[3 * a + 2] = 1;
  map.free_index.assign(fixed.size(), -1);
  for (int node : node_order)
    for (int dof = 3 * node; dof < 3 * node + 3; ++dof)
      if (!fixed[dof] && !map.tip_dof[dof]) {
        map.free_index[dof] = static_cast<int>(map.free_dofs.size());
        map.free_dofs.push_back(dof);
      }
  return map;
}

}  // namespace needlekit::fem::detail
