#include "needlekit/mesh/cell_replication.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <utility>


namespace needlekit::mesh {
namespace {

constexpr double kGridTolerance = 1e-9;   // of the pitch: a site on the grid, a margin of zero
constexpr double kFaceTolerance = 1e-7;   // of the pitch: a node on a cell face, a periodic partner

// Where a cell node lies along one axis: in the -side margin, on the cell's -face, inside the cell, on its +face, in
// the +side margin.
enum class Slot { LowMargin, LowFace, Inside, HighFace, HighMargin };

Slot slot_of(double coordinate, double pitch) {
  const double h = 0.5 * pitch, tolerance = kFaceTolerance * pitch;
  if (coordinate < -h - tolerance) return Slot::LowMargin;
  if (coordinate <= -h + tolerance) return Slot::LowFace;
  if (coordinate < h - tolerance) return Slot::Inside;
  if (coordinate <= h + tolerance) return Slot::HighFace;
  return Slot::HighMargin;
}

// The cell's nodes hashed by position, to find the node a translation by the pitch lands on.
class NodeLookup {
public:
  NodeLookup(const std::vector<Eigen::Vector3d>& nodes, double pitch)
      : nodes_(nodes), bucket_(1e-4 * pitch), tolerance_(kFaceTolerance * pitch) {
    for (std::size_t i = 0; i < nodes.size(); ++i) buckets_[key(bucket_of(nodes[i]))].push_back(static_cast<int>(i));
  }
  // The node within the tolerance of p, or -1.
  int find(const Eigen::Vector3d& p) const {
    const Eigen::Array3i b = bucket_of(p);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = buckets_.find(key(b + Eigen::Array3i(dx, dy, dz)));
          if (it == buckets_.end()) continue;
          for (int i : it->second) {
            if ((nodes_[static_cast<std::size_t>(i)] - p).lpNorm<Eigen::Infinity>() <= tolerance_) return i;
          }
        }
      }
    }
    return -1;
  }

private:
  Eigen::Array3i bucket_of(const Eigen::Vector3d& p) const { return (p.array() / bucket_).floor().cast<int>(); }
  static std::uint64_t key(const Eigen::Array3i& b) {
    const auto part = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v) & 0x1fffff); };
    return part(b.x()) | part(b.y()) << 21 | part(b.z()) << 42;
  }
  const std::vector<Eigen::Vector3d>& nodes_;
  double bucket_, tolerance_;
  std::unordered_map<std::uint64_t, std::vector<int>> buckets_;
};

// Each cell node's representative: the node itself, or for a node on a +face the node of the -face it is a copy of,
// with the shift (0 or 1 cell) in x and y that the representative needs to land on it.
struct Representative {
  int node = 0;
  int dx = 0, dy = 0;
};

std::vector<Representative> representatives(const TetMesh& cell, const Eigen::Vector2d& pitch) {
  const NodeLookup lookup(cell.nodes, pitch.minCoeff());
  std::vector<Representative> result(cell.nodes.size());
  for (std::size_t n = 0; n < cell.nodes.size(); ++n) {
    Representative r{static_cast<int>(n), 0, 0};
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Vector3d& p = cell.nodes[static_cast<std::size_t>(r.node)];
      if (slot_of(p[axis], pitch[axis]) != Slot::HighFace) continue;
      Eigen::Vector3d image = p;
      image[axis] -= pitch[axis];
      r.node = lookup.find(image);
      if (r.node < 0) {
        throw std::logic_error(fmt::format("array cell: the node at ({}, {}, {}) um on the cell's +{} face has no "
                                           "copy on its -{} face: the faces are not periodic",
                                           p.x() * 1e6, p.y() * 1e6, p.z() * 1e6, "xy"[axis], "xy"[axis]));
      }
      (axis == 0 ? r.dx : r.dy) = 1;
    }
    result[n] = r;
  }
  return result;
}

// How many copies a representative node has along one axis, and which of them the copy at cell index k is.
struct AxisCopies {
  int cells = 0;  // cells along the axis
  int count(Slot s) const { return s == Slot::LowFace ? cells + 1 : s == Slot::Inside ? cells : 1; }
  int index(Slot s, int k) const { return s == Slot::LowFace || s == Slot::Inside ? k : 0; }
};

// The copies (cell index range) of a piece along one axis: the -margin with cell 0, the cell at every index, the
// +margin with the last cell.
std::pair<int, int> piece_copies(int piece_axis_index, int cells) {
  if (piece_axis_index == 0) return {0, 1};
  if (piece_axis_index == 1) return {0, cells};
  return {cells - 1, cells};
}

}  // namespace

CellLattice square_lattice(double pitch) { return {pitch, pitch, {Eigen::Vector2d::Zero()}}; }

CellLattice hexagonal_lattice(double pitch) {
  const double row_pair = pitch * std::sqrt(3.0);
  return {pitch, row_pair, {{-0.25 * pitch, -0.25 * row_pair}, {0.25 * pitch, 0.25 * row_pair}}};
}

namespace {

// The corners (lowest, highest) of the points' bounding box.
std::pair<Eigen::Vector2d, Eigen::Vector2d> extent(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d low = points.front(), high = low;
  for (const Eigen::Vector2d& p : points) low = low.cwiseMin(p), high = high.cwiseMax(p);
  return {low, high};
}

// `sites` as every site of every cell of a grid of the lattice's cells (the grid's margins not yet set), or why not.
SiteGridCheck whole_cells(const std::vector<Eigen::Vector2d>& sites, const CellLattice& lattice) {
  const Eigen::Vector2d pitch(lattice.pitch_x, lattice.pitch_y);
  const auto [low, high] = extent(sites);
  const auto [lowest, highest] = extent(lattice.sites);  // the sites' extent within a cell
  SiteGrid g;
  g.first = low - lowest, g.pitch_x = pitch.x(), g.pitch_y = pitch.y(), g.sites = lattice.sites;
  const Eigen::Vector2d cells = ((high - low) - (highest - lowest)).cwiseQuotient(pitch);
  g.columns = static_cast<int>(std::lround(cells.x())) + 1;
  g.rows = static_cast<int>(std::lround(cells.y())) + 1;
  if (g.columns < 1 || g.rows < 1) return {std::nullopt, "sites that do not fill a cell of the lattice"};
  const std::size_t per_cell = lattice.sites.size();
  std::vector<char> seen(static_cast<std::size_t>(g.columns) * static_cast<std::size_t>(g.rows) * per_cell, 0);
  for (const Eigen::Vector2d& s : sites) {
    bool placed = false;
    for (std::size_t k = 0; k < per_cell && !placed; ++k) {
      const Eigen::Vector2d c = (s - g.first - lattice.sites[k]).cwiseQuotient(pitch);
      const Eigen::Vector2d r = c.array().round();
      if ((c - r).lpNorm<Eigen::Infinity>() > kGridTolerance || r.x() < 0 || r.y() < 0 || r.x() >= g.columns ||
          r.y() >= g.rows) {
        continue;
      }
      seen[(static_cast<std::size_t>(r.y()) * static_cast<std::size_t>(g.columns) + static_cast<std::size_t>(r.x())) *
               per_cell + k] = 1;
      placed = true;
    }
    if (!placed) return {std::nullopt, "sites off the lattice's grid of cells"};
  }
  if (std::count(seen.begin(), seen.end(), 1) != static_cast<long>(sites.size()) || sites.size() != seen.size()) {
    return {std::nullopt, per_cell > 1 ? "sites that are not every site of whole cells"
                                       : "sites that are not every point of a square grid"};
  }
  return {g, ""};
}

// A lattice of row pairs (hexagonal) with an odd number of rows: the cells hold every row but the last, and the last
// is the first site of each column's cell one row of cells higher, which the +y margin strip holds. The grid with
// that row as top_row_sites, or no grid.
std::optional<SiteGrid> cells_and_a_top_row(const std::vector<Eigen::Vector2d>& sites, const CellLattice& lattice) {
  if (lattice.sites.size() < 2) return std::nullopt;
  const double top = extent(sites).second.y();
  std::vector<Eigen::Vector2d> below, row;
  for (const Eigen::Vector2d& s : sites) (s.y() >= top - kGridTolerance * lattice.pitch_y ? row : below).push_back(s);
  if (below.size() < 2) return std::nullopt;
  std::optional<SiteGrid> g = whole_cells(below, lattice).grid;
  if (!g || row.size() != static_cast<std::size_t>(g->columns)) return std::nullopt;
  const Eigen::Vector2d in_last_cell = lattice.sites.front() + Eigen::Vector2d(0, lattice.pitch_y);
  const Eigen::Vector2d first_site = g->first + Eigen::Vector2d(0, (g->rows - 1) * lattice.pitch_y) + in_last_cell;
  std::vector<char> seen(static_cast<std::size_t>(g->columns), 0);
  for (const Eigen::Vector2d& s : row) {
    const double c = (s - first_site).x() / lattice.pitch_x, dy = (s - first_site).y() / lattice.pitch_y;
    const long column = std::lround(c);
    if (std::abs(c - static_cast<double>(column)) > kGridTolerance || std::abs(dy) > kGridTolerance || column < 0 ||
        column >= g->columns || seen[static_cast<std::size_t>(column)]) {
      return std::nullopt;
    }
    seen[static_cast<std::size_t>(column)] = 1;
  }
  g->top_row_sites = {in_last_cell};
  return g;
}

// A square lattice framed from needle to needle: cells between the needles, which stand on the cells' corners, for
// a block whose edge runs through a row or column of needles (a reduced model's symmetry plane through the middle
// row of an odd count). A needle amid the cells sees the four corners of one cell round it; one on the cells' outer
// corners also sees the margin strips.
std::optional<SiteGrid> corner_cells(const std::vector<Eigen::Vector2d>& sites, const CellLattice& lattice) {
  if (lattice.sites.size() != 1 || lattice.pitch_x != lattice.pitch_y) return std::nullopt;
  const Eigen::Vector2d pitch(lattice.pitch_x, lattice.pitch_y);
  const auto [low, high] = extent(sites);
  const Eigen::Vector2d cells = (high - low).cwiseQuotient(pitch);
  SiteGrid g;
  g.columns = static_cast<int>(std::lround(cells.x()));
  g.rows = static_cast<int>(std::lround(cells.y()));
  if (g.columns < 1 || g.rows < 1) return std::nullopt;
  std::vector<char> seen(static_cast<std::size_t>(g.columns + 1) * static_cast<std::size_t>(g.rows + 1), 0);
  for (const Eigen::Vector2d& s : sites) {
    const Eigen::Vector2d c = (s - low).cwiseQuotient(pitch), r = c.array().round();
    if ((c - r).lpNorm<Eigen::Infinity>() > kGridTolerance) return std::nullopt;
    seen[static_cast<std::size_t>(r.y()) * static_cast<std::size_t>(g.columns + 1) + static_cast<std::size_t>(r.x())] = 1;
  }
  if (std::count(seen.begin(), seen.end(), 1) != static_cast<long>(seen.size()) || sites.size() != seen.size()) {
    return std::nullopt;
  }
  g.first = low + 0.5 * pitch, g.pitch_x = pitch.x(), g.pitch_y = pitch.y();
  const double hx = 0.5 * pitch.x(), hy = 0.5 * pitch.y();
  g.sites = {{-hx, -hy}, {hx, -hy}, {-hx, hy}, {hx, hy}};
  g.sites_on_corners = true;
  return g;
}

// `g` with the block's margins beyond its cells, or why the block cannot hold the cells.
SiteGridCheck with_margins(const LayeredBlockOptions& o, SiteGrid g) {
  const Eigen::Vector2d pitch(g.pitch_x, g.pitch_y);
  const auto margin = [&](double value) { return std::abs(value) <= kGridTolerance * pitch.minCoeff() ? 0.0 : value; };
  const Eigen::Vector2d last = g.first + Eigen::Vector2d((g.columns - 1) * pitch.x(), (g.rows - 1) * pitch.y());
  g.margin_left = margin(g.first.x() - 0.5 * pitch.x() + 0.5 * o.width);
  g.margin_right = margin(0.5 * o.width - last.x() - 0.5 * pitch.x());
  g.margin_bottom = margin(g.first.y() - 0.5 * pitch.y() + 0.5 * o.length);
  g.margin_top = margin(0.5 * o.length - last.y() - 0.5 * pitch.y());
  for (double m : {g.margin_left, g.margin_right, g.margin_bottom, g.margin_top}) {
    if (m < 0) return {std::nullopt, "cells that leave the block (a needle less than half a pitch from its edge)"};
    if (m > 0 && m < 0.5 * o.size_at_site) {
      return {std::nullopt, fmt::format("a margin of {:.3g} um beyond the cells, thinner than half the tip size",
                                        m * 1e6)};
    }
  }
  for (const Eigen::Vector2d& s : g.top_row_sites) {
    if (s.y() >= 0.5 * pitch.y() + g.margin_top) return {std::nullopt, "a last row of needles on the block's edge"};
  }
  return {g, ""};
}

}  // namespace

SiteGridCheck site_grid(const LayeredBlockOptions& o, const CellLattice& lattice) {
  if (!(lattice.pitch_x > 0 && lattice.pitch_y > 0) || lattice.sites.empty()) return {std::nullopt, "no lattice"};
  if (o.insertion_sites.size() < 2) return {std::nullopt, "a single site"};
  SiteGridCheck centred = whole_cells(o.insertion_sites, lattice);
  if (!centred.grid) centred.grid = cells_and_a_top_row(o.insertion_sites, lattice);
  if (centred.grid) centred = with_margins(o, *centred.grid);
  if (centred.grid) return centred;
  const std::optional<SiteGrid> corners = corner_cells(o.insertion_sites, lattice);
  if (!corners) return centred;
  if (o.site_circle_radius > 0) {
    return {std::nullopt, centred.reason + "; with the needles on the cells' corners, their circles would cross the "
                                           "cells' faces"};
  }
  SiteGridCheck framed = with_margins(o, *corners);
  return framed.grid ? framed : centred;
}

TetMesh replicated_cells(const TetMesh& cell, const std::vector<int>& piece, const SiteGrid& grid) {
  const Eigen::Vector2d pitch(grid.pitch_x, grid.pitch_y);
  const std::vector<Representative> rep = representatives(cell, pitch);
  const AxisCopies along_x{grid.columns}, along_y{grid.rows};
  // Each representative's block of dense keys: count_x * count_y copies.
  std::vector<std::int64_t> first_key(cell.nodes.size() + 1, 0);
  for (std::size_t n = 0; n < cell.nodes.size(); ++n) {
    const std::int64_t copies = rep[n].node == static_cast<int>(n)
                                    ? std::int64_t{along_x.count(slot_of(cell.nodes[n].x(), pitch.x()))} *
                                          along_y.count(slot_of(cell.nodes[n].y(), pitch.y()))
                                    : 0;
    first_key[n + 1] = first_key[n] + copies;
  }
  std::vector<int> id_of_key(static_cast<std::size_t>(first_key.back()), -1);
  std::vector<std::vector<int>> tets_of_piece(9);
  for (std::size_t e = 0; e < cell.tets.size(); ++e) tets_of_piece.at(static_cast<std::size_t>(piece[e])).push_back(static_cast<int>(e));
  TetMesh block;
  block.layers = cell.layers;
  // A cell node in the copy at cell (kx, ky): its representative's copy, numbered when first used.
  const auto node_id = [&](int n, int kx, int ky) {
    const Representative& r = rep[static_cast<std::size_t>(n)];
    const Eigen::Vector3d& q = cell.nodes[static_cast<std::size_t>(r.node)];
    const Slot sx = slot_of(q.x(), pitch.x()), sy = slot_of(q.y(), pitch.y());
    const int ix = kx + r.dx, iy = ky + r.dy;
    const std::int64_t key = first_key[static_cast<std::size_t>(r.node)] + along_x.index(sx, ix) +
                             std::int64_t{along_x.count(sx)} * along_y.index(sy, iy);
    int& id = id_of_key[static_cast<std::size_t>(key)];
    if (id < 0) {
      id = static_cast<int>(block.nodes.size());
      block.nodes.push_back(q + Eigen::Vector3d(grid.first.x() + ix * pitch.x(), grid.first.y() + iy * pitch.y(), 0));
    }
    return id;
  };
  for (int py = 0; py < 3; ++py) {
    const auto [y0, y1] = piece_copies(py, grid.rows);
    for (int ky = y0; ky < y1; ++ky) {
      for (int px = 0; px < 3; ++px) {
        const auto [x0, x1] = piece_copies(px, grid.columns);
        for (int kx = x0; kx < x1; ++kx) {
          for (int e : tets_of_piece[static_cast<std::size_t>(3 * py + px)]) {
            const std::array<int, 4>& t = cell.tets[static_cast<std::size_t>(e)];
            block.tets.push_back({node_id(t[0], kx, ky), node_id(t[1], kx, ky), node_id(t[2], kx, ky),
                                  node_id(t[3], kx, ky)});
            block.tet_layer.push_back(cell.tet_layer[static_cast<std::size_t>(e)]);
          }
        }
      }
    }
  }
  return block;
}

}  // namespace needlekit::mesh
