#include "needlekit/mesh/rezoned_mesh.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <Eigen/LU>

#include <algorithm>
#include <optional>
#include <set>
#include <stdexcept>

#include "gmsh_module.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/mesh_validation.hpp"
#include "needlekit/mesh/tet_adjacency.hpp"
#include "needlekit/mesh/tet_locator.hpp"

namespace needlekit::mesh {
namespace {

// Per node of the deformed mesh: the mean length of its edges, m (each edge counted once per tetrahedron it is in).
std::vector<double> deformed_node_sizes(const TetMesh& deformed) {
  std::vector<double> sum(deformed.nodes.size(), 0.0);
  std::vector<int> count(deformed.nodes.size(), 0);
  for (const std::array<int, 4>& t : deformed.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const std::size_t a = static_cast<std::size_t>(t[i]), b = static_cast<std::size_t>(t[j]);
        const double l = (deformed.nodes[a] - deformed.nodes[b]).norm();
        sum[a] += l, sum[b] += l;
        ++count[a], ++count[b];
      }
  for (std::size_t a = 0; a < sum.size(); ++a) sum[a] /= std::max(count[a], 1);
  return sum;
}

// The edges [X1 - X0, X2 - X0, X3 - X0] of tetrahedron k of `mesh` from its nodes, m.
Eigen::Matrix3d nodal_edges(const TetMesh& mesh, std::size_t k) {
  const std::array<int, 4>& t = mesh.tets[k];
  Eigen::Matrix3d edges;
  const Eigen::Vector3d& x0 = mesh.nodes[static_cast<std::size_t>(t[0])];
  for (std::size_t i = 0; i < 3; ++i)
    edges.col(static_cast<Eigen::Index>(i)) = mesh.nodes[static_cast<std::size_t>(t[i + 1])] - x0;
  return edges;
}

// The tetrahedra to mesh anew: those whose J = det F (`volume_ratios`, per old tetrahedron) is below `volume_ratio`,
// grown by `rings` rings of neighbours (tetrahedra sharing a node); all of them when none is below it (or
// volume_ratio is 0).
std::vector<char> crushed_region(const TetMesh& reference, const std::vector<double>& volume_ratios,
                                 double volume_ratio, int rings) {
  std::vector<char> region(reference.tets.size(), 0);
  bool any = false;
  for (std::size_t e = 0; e < reference.tets.size(); ++e)
    if (volume_ratios[e] < volume_ratio) region[e] = 1, any = true;
  if (!any) return std::vector<char>(reference.tets.size(), 1);
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> touched(reference.nodes.size(), 0);
    for (std::size_t e = 0; e < reference.tets.size(); ++e)
      if (region[e])
        for (int a : reference.tets[e]) touched[static_cast<std::size_t>(a)] = 1;
    for (std::size_t e = 0; e < reference.tets.size(); ++e)
      for (int a : reference.tets[e]) region[e] |= touched[static_cast<std::size_t>(a)];
  }
  return region;
}

// The deformed boundary of the region's tetrahedra (the cavity that is refilled) as a surface of its own nodes
// (numbered in ascending old index), with the old index of each.
detail::SurfaceToFill cavity_boundary(const TetMesh& deformed, const std::vector<char>& region,
                                      std::vector<int>& old_of_surface_node) {
  TetMesh cavity;
  cavity.nodes = deformed.nodes;
  for (std::size_t e = 0; e < deformed.tets.size(); ++e)
    if (region[e]) cavity.tets.push_back(deformed.tets[e]);
  const BoundarySurface boundary = boundary_surface(cavity, tet_topology(cavity));
  std::vector<int> surface_index(deformed.nodes.size(), -1);
  for (const std::array<int, 3>& t : boundary.triangles)
    for (int a : t) surface_index[static_cast<std::size_t>(a)] = 0;
  detail::SurfaceToFill surface;
  for (std::size_t a = 0; a < deformed.nodes.size(); ++a) {
    if (surface_index[a] < 0) continue;
    surface_index[a] = static_cast<int>(surface.nodes.size());
    surface.nodes.push_back(deformed.nodes[a]);
    old_of_surface_node.push_back(static_cast<int>(a));
  }
  for (const std::array<int, 3>& t : boundary.triangles) {
    surface.triangles.push_back({surface_index[static_cast<std::size_t>(t[0])],
                                 surface_index[static_cast<std::size_t>(t[1])],
                                 surface_index[static_cast<std::size_t>(t[2])]});
  }
  return surface;
}

constexpr int kSmoothingRounds = 8;
constexpr double kWorstReferenceQuality = 1e-3;  // gamma of a new tetrahedron carried back, below: smoothed or split

// Whether tetrahedron t of `mesh` is right-handed and not degenerate enough to be smoothed or split.
bool well_shaped(const TetMesh& mesh, const std::array<int, 4>& t) {
  const auto p = [&](int i) -> const Eigen::Vector3d& { return mesh.nodes[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])]; };
  return signed_volume(p(0), p(1), p(2), p(3)) > 0 && tet_quality(p(0), p(1), p(2), p(3)) >= kWorstReferenceQuality;
}

// A new tetrahedron whose four nodes are all on the boundary can span a convex bend of the deformed surface (round
// a needle's rim): its four nodes then lie on the flat reference surface, and carried back it is flat. No inner
// point can mend it, since every face of a flat tetrahedron has a twin of the other orientation. Its longest edge
// inside the tissue (not an edge of the boundary) is a chord under the bend instead: the chord is split at its
// deformed midpoint (a new inner node, appended to `deformed`, its reference position not yet known), and every
// tetrahedron that holds the chord is split in two there. The halves of the flat tetrahedron each keep one
// boundary face and take the midpoint, which is carried back under the surface. Conforming: the split runs round the
// whole chord.
void split_chords(TetMesh& deformed, const std::vector<std::array<int, 3>>& boundary,
                  const std::vector<Eigen::Vector3d>& kept_reference, int kept_nodes) {
  std::set<std::pair<int, int>> boundary_edges;
  for (const std::array<int, 3>& t : boundary)
    for (int k = 0; k < 3; ++k) boundary_edges.insert(std::minmax(t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]));
  TetMesh reference_of_kept;
  reference_of_kept.nodes = kept_reference;
  std::set<std::pair<int, int>> chords;
  for (const std::array<int, 4>& t : deformed.tets) {
    if (std::any_of(t.begin(), t.end(), [&](int a) { return a >= kept_nodes; }) || well_shaped(reference_of_kept, t))
      continue;
    std::pair<int, int> longest{-1, -1};
    double length = -1;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const std::pair<int, int> edge = std::minmax(t[static_cast<std::size_t>(i)], t[static_cast<std::size_t>(j)]);
        const double l = (deformed.nodes[static_cast<std::size_t>(edge.first)] - deformed.nodes[static_cast<std::size_t>(edge.second)]).norm();
        if (!boundary_edges.count(edge) && l > length) longest = edge, length = l;
      }
    if (longest.first >= 0) chords.insert(longest);
  }
  for (const std::pair<int, int>& chord : chords) {
    const int m = static_cast<int>(deformed.nodes.size());
    deformed.nodes.push_back(0.5 * (deformed.nodes[static_cast<std::size_t>(chord.first)] +
                                    deformed.nodes[static_cast<std::size_t>(chord.second)]));
    const std::size_t tets = deformed.tets.size();
    for (std::size_t e = 0; e < tets; ++e) {
      std::array<int, 4>& t = deformed.tets[e];
      const auto p = std::find(t.begin(), t.end(), chord.first), q = std::find(t.begin(), t.end(), chord.second);
      if (p == t.end() || q == t.end()) continue;
      std::array<int, 4> other = t;
      other[static_cast<std::size_t>(q - t.begin())] = m;
      *p = m;
      deformed.tets.push_back(other);
    }
  }
  deformed.tet_layer.resize(deformed.tets.size(), 0);
}

// A new tetrahedron that comes back inverted or degenerate spans a place where the old mapping bends sharply. Its
// inner nodes (never a kept node) are moved in the deformed state `moved` halfway to the centroid of their
// neighbours (one Laplacian smoothing step, Field 1988), where every tetrahedron round the node stays right-handed.
// The caller carries them back again. Returns the nodes moved.
std::vector<std::size_t> smoothed_inner_nodes(const TetMesh& pulled_back, std::vector<Eigen::Vector3d>& moved,
                                              const std::vector<std::array<int, 4>>& tets, int kept_nodes) {
  std::vector<char> bad_node(moved.size(), 0);
  for (const std::array<int, 4>& t : pulled_back.tets) {
    if (well_shaped(pulled_back, t)) continue;
    for (int a : t)
      if (a >= kept_nodes) bad_node[static_cast<std::size_t>(a)] = 1;
  }
  std::vector<std::vector<int>> tets_of(moved.size());
  for (std::size_t e = 0; e < tets.size(); ++e)
    for (int a : tets[e])
      if (bad_node[static_cast<std::size_t>(a)]) tets_of[static_cast<std::size_t>(a)].push_back(static_cast<int>(e));
  const auto right_handed = [&](std::size_t a) {
    for (int e : tets_of[a]) {
      const std::array<int, 4>& t = tets[static_cast<std::size_t>(e)];
      const auto p = [&](int i) -> const Eigen::Vector3d& { return moved[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])]; };
      if (!(signed_volume(p(0), p(1), p(2), p(3)) > 0)) return false;
    }
    return true;
  };
  std::vector<std::size_t> smoothed;
  for (std::size_t a = 0; a < moved.size(); ++a) {
    if (!bad_node[a]) continue;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    int neighbours = 0;
    for (int e : tets_of[a])
      for (int b : tets[static_cast<std::size_t>(e)])
        if (static_cast<std::size_t>(b) != a) centroid += moved[static_cast<std::size_t>(b)], ++neighbours;
    const Eigen::Vector3d before = moved[a];
    moved[a] = 0.5 * (before + centroid / neighbours);
    if (right_handed(a)) {
      smoothed.push_back(a);
    } else {
      moved[a] = before;
    }
  }
  return smoothed;
}

// The old mesh in its deformed state, with what every refill attempt needs of it.
struct OldMesh {
  OldMesh(const TetMesh& reference_mesh, const std::vector<Eigen::Vector3d>& old_displacement)
      : reference(reference_mesh), displacement(old_displacement), deformed(deformed_mesh(reference, displacement)),
        locator(deformed.nodes, deformed.tets), node_size(deformed_node_sizes(deformed)),
        own(reference.tets.size(), nullptr) {
    for (const OwnReference& r : reference.own_reference) own[static_cast<std::size_t>(r.tet)] = &r.edges;
    for (std::size_t k = 0; k < reference.tets.size(); ++k)
      volume_ratios.push_back(deformation_gradient(static_cast<int>(k)).determinant());
  }
  // The region of crushed_region and its boundary (cavity_boundary) for this attempt.
  void take_out(const RezoneOptions& options, int rings) {
    region = crushed_region(reference, volume_ratios, options.volume_ratio, rings);
    surface_node.clear();
    surface = cavity_boundary(deformed, region, surface_node);
  }
  static TetMesh deformed_mesh(const TetMesh& reference, const std::vector<Eigen::Vector3d>& displacement) {
    TetMesh deformed = reference;
    for (std::size_t a = 0; a < deformed.nodes.size(); ++a) deformed.nodes[a] += displacement[a];
    return deformed;
  }
  // The old tetrahedron k's deformation gradient: its deformed edges times its reference edges' inverse (its own
  // reference's, if it has one).
  Eigen::Matrix3d deformation_gradient(int k) const {
    const std::size_t e = static_cast<std::size_t>(k);
    return nodal_edges(deformed, e) * (own[e] ? *own[e] : nodal_edges(reference, e)).inverse();
  }
  // m: the mean edge length of the old tetrahedra at x, interpolated from their nodes.
  double size_at(const Eigen::Vector3d& x) const {
    const TetLocation at = locator.locate(x);
    const Eigen::Vector4d w = at.barycentric.cwiseMax(0.0);
    double h = 0;
    for (int i = 0; i < 4; ++i)
      h += w[i] * node_size[static_cast<std::size_t>(deformed.tets[static_cast<std::size_t>(at.tet)][static_cast<std::size_t>(i)])];
    return h / w.sum();
  }

  const TetMesh& reference;
  const std::vector<Eigen::Vector3d>& displacement;
  TetMesh deformed;
  TetLocator locator;
  std::vector<double> node_size;  // m, deformed_node_sizes
  std::vector<const Eigen::Matrix3d*> own;  // per old tetrahedron: its own reference edges, or null
  std::vector<double> volume_ratios;        // per old tetrahedron: J = det F
  std::vector<char> region;       // per old tetrahedron: meshed anew (crushed_region)
  std::vector<int> surface_node;  // per node of `surface`: its old node
  detail::SurfaceToFill surface;  // the region's deformed boundary, without sizes
};

// Gmsh's Delaunay makes tetrahedra about 1/0.75 times the edge length asked for: this factor on the old mesh's edge
// lengths keeps the element count (measured on the 5.5 um sharp bevel: 58,179 -> 59,421 -> 60,327 -> 61,519
// tetrahedra over three rezonings of the whole tissue). The other factors are the retries: a new tetrahedron that
// straddles a sharp bend of the old mapping (the surface layer sheared along a bevel by more than an element) comes
// back inverted, and a slightly different Delaunay mesh often has none.
constexpr std::array<double, 3> kSizeFactors{0.75, 0.7, 0.8};
// Then the same with a region grown by this many more rings (another boundary, so another Delaunay mesh).
constexpr int kMoreRings = 2;

// The refilled region `cavity` (its surface's old nodes first) joined to the old tetrahedra outside the region: the
// old nodes still in use first, in their old order, then the region's new nodes.
RezonedMesh with_the_rest(const OldMesh& old, RezonedMesh cavity) {
  std::vector<int> index(old.reference.nodes.size(), -1);
  for (std::size_t e = 0; e < old.reference.tets.size(); ++e)
    if (!old.region[e])
      for (int a : old.reference.tets[e]) index[static_cast<std::size_t>(a)] = 0;
  for (int i = 0; i < cavity.kept_nodes; ++i) index[static_cast<std::size_t>(cavity.old_node[static_cast<std::size_t>(i)])] = 0;
  RezonedMesh out;
  out.mesh.layers = old.reference.layers;
  for (std::size_t a = 0; a < index.size(); ++a) {
    if (index[a] < 0) continue;
    index[a] = static_cast<int>(out.mesh.nodes.size());
    out.mesh.nodes.push_back(old.reference.nodes[a]);
    out.displacement.push_back(old.displacement[a]);
    out.old_node.push_back(static_cast<int>(a));
  }
  out.kept_nodes = static_cast<int>(out.mesh.nodes.size());
  std::vector<int> kept_tet(old.reference.tets.size(), -1);
  for (std::size_t e = 0; e < old.reference.tets.size(); ++e) {
    if (old.region[e]) continue;
    std::array<int, 4> t = old.reference.tets[e];
    for (int& a : t) a = index[static_cast<std::size_t>(a)];
    kept_tet[e] = static_cast<int>(out.mesh.tets.size());
    out.mesh.tets.push_back(t);
    out.mesh.tet_layer.push_back(old.reference.tet_layer[e]);
  }
  for (const OwnReference& r : old.reference.own_reference)
    if (kept_tet[static_cast<std::size_t>(r.tet)] >= 0) out.mesh.own_reference.push_back({kept_tet[static_cast<std::size_t>(r.tet)], r.edges});
  const int first_new_tet = static_cast<int>(out.mesh.tets.size());
  for (const OwnReference& r : cavity.mesh.own_reference) out.mesh.own_reference.push_back({first_new_tet + r.tet, r.edges});
  const auto new_index = [&](int a) {
    return a < cavity.kept_nodes ? index[static_cast<std::size_t>(cavity.old_node[static_cast<std::size_t>(a)])]
                                 : out.kept_nodes + (a - cavity.kept_nodes);
  };
  for (std::size_t e = 0; e < cavity.mesh.tets.size(); ++e) {
    std::array<int, 4> t = cavity.mesh.tets[e];
    for (int& a : t) a = new_index(a);
    out.mesh.tets.push_back(t);
    out.mesh.tet_layer.push_back(cavity.mesh.tet_layer[e]);
  }
  for (std::size_t a = static_cast<std::size_t>(cavity.kept_nodes); a < cavity.mesh.nodes.size(); ++a) {
    out.mesh.nodes.push_back(cavity.mesh.nodes[a]);
    out.displacement.push_back(cavity.displacement[a]);
    out.old_node.push_back(-1);
  }
  return out;
}

// What smoothing leaves inverted or degenerate in `out` (the cavity's new mesh; `filled` its deformed state) takes its
// own reference shape from the old deformation gradient at its deformed centroid: its F at the transfer is then the
// old element's (mesh::OwnReference). False (and `why`) when that gradient gives no shape either.
bool give_own_references(const OldMesh& old, const TetMesh& filled, RezonedMesh& out, std::string& why) {
  const TetMeshCheck check = tet_mesh_check(out.mesh, {}, "rezoned tissue");
  std::vector<int> bad = check.inverted;
  bad.insert(bad.end(), check.degenerate.begin(), check.degenerate.end());
  std::sort(bad.begin(), bad.end());
  bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
  for (int e : bad) {
    const std::array<int, 4>& t = filled.tets[static_cast<std::size_t>(e)];
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Matrix3d deformed_edges;
    for (int i = 0; i < 4; ++i) centroid += 0.25 * filled.nodes[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])];
    for (int i = 0; i < 3; ++i)
      deformed_edges.col(i) = filled.nodes[static_cast<std::size_t>(t[static_cast<std::size_t>(i) + 1])] - filled.nodes[static_cast<std::size_t>(t[0])];
    const Eigen::Matrix3d old_gradient = old.deformation_gradient(old.locator.locate(centroid).tet);
    const Eigen::Matrix3d edges = old_gradient.inverse() * deformed_edges;
    if (!(old_gradient.determinant() > 0) ||
        tet_quality(Eigen::Vector3d::Zero(), edges.col(0), edges.col(1), edges.col(2)) < kWorstReferenceQuality) {
      why = fmt::format("rezoning: a new tetrahedron of {} is inverted when carried back to the reference "
                        "configuration, and the old deformation gradient there does not give it a shape either",
                        out.mesh.tets.size());
      return false;
    }
    out.mesh.own_reference.push_back({e, edges});
  }
  return true;
}

// The deformed tissue refilled with `surface`'s sizes and carried back, or nothing (and `why`) when Gmsh cannot fill
// it or a new tetrahedron comes back inverted or degenerate.
std::optional<RezonedMesh> refilled(const OldMesh& old, const detail::SurfaceToFill& surface, std::string& why) {
  RezonedMesh out;
  out.old_node = old.surface_node;
  out.kept_nodes = static_cast<int>(out.old_node.size());
  detail::GmshError error;
  TetMesh filled;
  {
    const std::lock_guard<std::mutex> lock(detail::gmsh_call_mutex());
    filled = detail::gmsh_module().refill(surface, error);
  }
  if (error.kind != detail::GmshErrorKind::None) {  // e.g. a deformed boundary that touches itself
    why = error.message;
    return std::nullopt;
  }
  for (std::size_t a = 0; a < static_cast<std::size_t>(out.kept_nodes); ++a) {  // back from Gmsh's units exactly
    if ((filled.nodes[a] - surface.nodes[a]).norm() > 1e-9 * surface.nodes[a].norm() + 1e-15)
      throw std::logic_error("rezoning: Gmsh renumbered the kept boundary nodes");
    filled.nodes[a] = surface.nodes[a];
  }
  reoriented_count(filled);  // Gmsh's tetrahedra are not all right-handed
  std::vector<Eigen::Vector3d> kept_reference;
  for (int a : out.old_node) kept_reference.push_back(old.reference.nodes[static_cast<std::size_t>(a)]);
  split_chords(filled, surface.triangles, kept_reference, out.kept_nodes);

  // Pull the new nodes back: the kept ones exactly, the inner ones through the old element that holds them.
  out.old_node.resize(filled.nodes.size(), -1);
  out.mesh.layers = old.reference.layers;
  out.mesh.tets = filled.tets;
  out.mesh.nodes.resize(filled.nodes.size());
  out.displacement.resize(filled.nodes.size());
  const auto pull_back = [&](std::size_t a) {
    if (out.old_node[a] >= 0) {
      const std::size_t kept = static_cast<std::size_t>(out.old_node[a]);
      out.mesh.nodes[a] = old.reference.nodes[kept];
      out.displacement[a] = old.displacement[kept];
      return;
    }
    const TetLocation at = old.locator.locate(filled.nodes[a]);
    const std::array<int, 4>& t = old.reference.tets[static_cast<std::size_t>(at.tet)];
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) x += at.barycentric[i] * old.reference.nodes[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])];
    out.mesh.nodes[a] = x;
    out.displacement[a] = filled.nodes[a] - x;
  };
  tbb::parallel_for(std::size_t{0}, filled.nodes.size(), pull_back);
  for (int round = 0; round < kSmoothingRounds; ++round) {
    const std::vector<std::size_t> moved = smoothed_inner_nodes(out.mesh, filled.nodes, filled.tets, out.kept_nodes);
    if (moved.empty()) break;
    for (std::size_t a : moved) pull_back(a);
  }
  out.mesh.tet_layer.resize(filled.tets.size());
  for (std::size_t e = 0; e < filled.tets.size(); ++e) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int a : filled.tets[e]) centroid += 0.25 * filled.nodes[static_cast<std::size_t>(a)];
    out.mesh.tet_layer[e] = old.reference.tet_layer[static_cast<std::size_t>(old.locator.locate(centroid).tet)];
  }
  if (!give_own_references(old, filled, out, why)) return std::nullopt;
  return with_the_rest(old, std::move(out));
}

}  // namespace

RezonedMesh rezoned_mesh(const TetMesh& reference, const std::vector<Eigen::Vector3d>& displacement,
                         const RezoneOptions& options) {
  if (displacement.size() != reference.nodes.size())
    throw InvalidInput(fmt::format("rezoning: {} displacements for {} nodes", displacement.size(),
                                   reference.nodes.size()));
  OldMesh old(reference, displacement);
  std::string why;
  for (int rings : {options.rings, options.rings + kMoreRings}) {
    old.take_out(options, rings);
    for (double factor : kSizeFactors) {
      detail::SurfaceToFill surface = old.surface;
      surface.size = options.size ? options.size : [&](const Eigen::Vector3d& x) { return factor * old.size_at(x); };
      std::optional<RezonedMesh> rezoned = refilled(old, surface, why);
      if (rezoned) return std::move(*rezoned);
      if (options.size) break;  // the same sizes would give the same mesh
    }
  }
  throw std::runtime_error(why);
}

}  // namespace needlekit::mesh
