#include "mirrored_cell.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace needlekit::mesh::detail {
namespace {

constexpr double kPlaneTolerance = 1e-9;  // of the pitch: a node on a mirror plane

// Equal margins, or none on one side (a symmetry plane of a reduced model); with sites on the corners, none or at
// least half a pitch (the quadrant's margin beyond its site is half a pitch wider than the one beyond the quadrant).
bool mirrorable_margins(double low, double high, double pitch, bool sites_on_corners) {
  const double margin = std::max(low, high);
  return (low == 0 || high == 0 || std::abs(low - high) <= kPlaneTolerance * pitch) &&
         (!sites_on_corners || margin == 0 || margin >= 0.5 * pitch);
}

}  // namespace

bool mirrors_from_a_quadrant(const CellLayout& layout, const LayeredBlockOptions& options) {
  const bool one_central_site = layout.sites.size() == 1 && layout.sites.front().norm() <= kPlaneTolerance * layout.pitch_x;
  return (one_central_site || layout.sites_on_corners) && layout.top_row_sites.empty() &&
         options.site_circle_radius == 0 &&
         mirrorable_margins(layout.margin_left, layout.margin_right, layout.pitch_x, layout.sites_on_corners) &&
         mirrorable_margins(layout.margin_bottom, layout.margin_top, layout.pitch_y, layout.sites_on_corners);
}

CellBlockMesh mirrored_cell(const CellBlockMesh& quadrant, const CellLayout& layout) {
  const TetMesh& q = quadrant.mesh;
  const int n = static_cast<int>(q.nodes.size());
  // The quadrant with its site on the cell's centre: nodes (x, y, z), on the planes x = 0 and y = 0 exactly; the
  // margin pieces on the other side than the layout's margins are not used.
  std::vector<Eigen::Vector3d> nodes = q.nodes;
  std::vector<int> piece = quadrant.piece;
  const int unused = layout.sites_on_corners ? 2 : 0;
  for (int& k : piece) {
    if (k % 3 == unused || k / 3 == unused) k = -1;
  }
  if (layout.sites_on_corners) {
    for (Eigen::Vector3d& p : nodes) p.head<2>() = Eigen::Vector2d(0.5 * layout.pitch_x, 0.5 * layout.pitch_y) - p.head<2>();
    for (int& k : piece) k = k < 0 ? k : 3 * (2 - k / 3) + (2 - k % 3);
  }
  for (Eigen::Vector3d& p : nodes) {
    if (std::abs(p.x()) <= kPlaneTolerance * layout.pitch_x) p.x() = 0;
    if (std::abs(p.y()) <= kPlaneTolerance * layout.pitch_y) p.y() = 0;
  }
  const bool margin[2][2] = {{layout.margin_left > 0, layout.margin_right > 0},
                             {layout.margin_bottom > 0, layout.margin_top > 0}};
  CellBlockMesh cell;
  cell.mesh.layers = q.layers;
  // image[m * n + i]: node i of the quadrant in the image m (bit 0: mirrored in x, bit 1: in y), -1 before first use.
  std::vector<int> image(4 * static_cast<std::size_t>(n), -1);
  const auto node_of = [&](int i, int m) {
    const Eigen::Vector3d& p = nodes[static_cast<std::size_t>(i)];
    const int own = (p.x() == 0 ? m & ~1 : m) & (p.y() == 0 ? ~2 : ~0);  // a node on a plane is its own image there
    int& index = image[static_cast<std::size_t>(own) * n + i];
    if (index < 0) {
      index = static_cast<int>(cell.mesh.nodes.size());
      cell.mesh.nodes.emplace_back((own & 1) ? -p.x() : p.x(), (own & 2) ? -p.y() : p.y(), p.z());
    }
    return index;
  };
  for (int m = 0; m < 4; ++m) {
    const bool flip_x = m & 1, flip_y = m & 2;
    for (std::size_t t = 0; t < q.tets.size(); ++t) {
      if (piece[t] < 0) continue;
      const int px = piece[t] % 3, py = piece[t] / 3;  // 1 the cell, 2 the margin beyond it
      const int to_x = flip_x ? 2 - px : px, to_y = flip_y ? 2 - py : py;
      if ((to_x != 1 && !margin[0][to_x / 2]) || (to_y != 1 && !margin[1][to_y / 2])) continue;
      std::array<int, 4> tet{};
      for (int a = 0; a < 4; ++a) tet[static_cast<std::size_t>(a)] = node_of(q.tets[t][static_cast<std::size_t>(a)], m);
      if (flip_x != flip_y) std::swap(tet[0], tet[1]);  // one reflection: the orientation reverses
      cell.mesh.tets.push_back(tet);
      cell.mesh.tet_layer.push_back(q.tet_layer[t]);
      cell.piece.push_back(3 * to_y + to_x);
    }
  }
  return cell;
}

}  // namespace needlekit::mesh::detail
