#include "needlekit/mesh/structured_block_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "needlekit/core/errors.hpp"

namespace needlekit::mesh {

namespace {

void require(bool ok, const std::string& field, double value, const std::string& expected) {
  if (!ok) {
    std::ostringstream s;
    s << "structured block: " << field << " = " << value << ", expected " << expected;
    throw InvalidInput(s.str());
  }
}

// Coordinates of one side of the focus: m cells over `length`, spacing growing geometrically from the focus so that
// the last cell is `grading` times the first. Returns offsets from the focus (0 excluded, `length` last).
std::vector<double> graded_offsets(int m, double length, double grading) {
  std::vector<double> out;
  if (m <= 0) return out;
  const double q = m > 1 ? std::pow(grading, 1.0 / (m - 1)) : 1.0;
  double sum = 0, h = 1;
  for (int k = 0; k < m; ++k, h *= q) sum += h;
  double x = 0;
  h = length / sum;
  for (int k = 0; k < m; ++k, h *= q) {
    x += h;
    out.push_back(k + 1 == m ? length : x);
  }
  return out;
}

// Offsets from the focus: `core` equal cells over `half`, then m cells growing geometrically from that spacing to
// `length`.
std::vector<double> cored_offsets(int core, double half, int m, double length) {
  std::vector<double> out;
  const double h = half / core;
  for (int k = 1; k <= core; ++k) out.push_back(k * h);
  const double rest = length - half;
  auto total = [&](double q) { return std::abs(q - 1) < 1e-12 ? m * h : h * q * (std::pow(q, m) - 1) / (q - 1); };
  double qa = 1e-3, qb = 100;
  for (int it = 0; it < 200; ++it) {
    const double qm = 0.5 * (qa + qb);
    (total(qm) < rest ? qa : qb) = qm;
  }
  const double q = 0.5 * (qa + qb);
  double x = half, step = h;
  for (int k = 0; k < m; ++k) {
    step *= q;
    x += step;
    out.push_back(k + 1 == m ? length : x);
  }
  return out;
}

std::vector<double> cored_axis(double lo, double hi, double focus, int cells, int core, double half) {
  const double span = hi - lo;
  const bool at_lo = focus - lo <= 1e-12 * span;  // focus on the low face: one-sided (symmetry models)
  int left = at_lo ? 0 : static_cast<int>(std::lround(cells * (focus - lo) / span));
  if (!at_lo) left = std::clamp(left, core + 1, cells - core - 1);
  std::vector<double> c;
  if (!at_lo) {
    const auto lo_side = cored_offsets(core, half, left - core, focus - lo);
    for (auto it = lo_side.rbegin(); it != lo_side.rend(); ++it) c.push_back(focus - *it);
  }
  c.push_back(at_lo ? lo : focus);
  for (double o : cored_offsets(core, half, cells - left - core, hi - focus)) c.push_back(focus + o);
  return c;
}

std::vector<double> axis(double lo, double hi, double focus, int cells, double grading) {
  const double span = hi - lo;
  int left = static_cast<int>(std::lround(cells * (focus - lo) / span));
  if (focus - lo > 1e-12 * span && left == 0) left = 1;
  if (hi - focus > 1e-12 * span && left == cells) left = cells - 1;
  std::vector<double> c;
  const auto lo_side = graded_offsets(left, focus - lo, grading);
  for (auto it = lo_side.rbegin(); it != lo_side.rend(); ++it) c.push_back(focus - *it);
  if (left == 0) c.push_back(lo);
  if (left > 0) c.push_back(focus);
  for (double o : graded_offsets(cells - left, hi - focus, grading)) c.push_back(focus + o);
  c.front() = lo;
  c.back() = hi;
  return c;
}

void validate(const StructuredBlockOptions& o) {
  require(o.width > 0 && std::isfinite(o.width), "width", o.width, "> 0 m");
  require(o.length > 0 && std::isfinite(o.length), "length", o.length, "> 0 m");
  require(o.height > 0 && std::isfinite(o.height), "height", o.height, "> 0 m");
  require(o.nx >= 1, "nx", o.nx, ">= 1");
  require(o.ny >= 1, "ny", o.ny, ">= 1");
  require(o.nz >= 1, "nz", o.nz, ">= 1");
  require(o.tets_per_hex == 5 || o.tets_per_hex == 6, "tets_per_hex", o.tets_per_hex, "5 or 6");
  require(o.grading >= 1 && std::isfinite(o.grading), "grading", o.grading, ">= 1");
  require(std::abs(o.focus.x()) <= o.width / 2, "focus x", o.focus.x(), "inside the top face");
  require(std::abs(o.focus.y()) <= o.length / 2, "focus y", o.focus.y(), "inside the top face");
  if (o.core_cells <= 0) return;
  require(o.core_half_width > 0, "core_half_width", o.core_half_width, "> 0 m");
  const bool corner_x = o.focus.x() <= -o.width / 2 * (1 - 1e-12), corner_y = o.focus.y() <= -o.length / 2 * (1 - 1e-12);
  require(o.nx > (corner_x ? 1 : 2) * o.core_cells && o.ny > (corner_y ? 1 : 2) * o.core_cells, "core_cells",
          o.core_cells, "< nx / 2 and < ny / 2 (< nx, ny for a focus on the low face)");
  require(o.nz > o.core_cells, "core_cells", o.core_cells, "< nz");
  require(o.focus.x() + o.core_half_width < o.width / 2 && o.focus.y() + o.core_half_width < o.length / 2 &&
              o.core_half_width < o.height,
          "core_half_width", o.core_half_width, "a core inside the block");
}

// The grid's nodes: graded (or cored) coordinates along x, y and z, z from the bottom up, finest at the top.
std::vector<Eigen::Vector3d> grid_nodes(const StructuredBlockOptions& o) {
  const bool cored = o.core_cells > 0;
  const auto xs = cored ? cored_axis(-o.width / 2, o.width / 2, o.focus.x(), o.nx, o.core_cells, o.core_half_width)
                        : axis(-o.width / 2, o.width / 2, o.focus.x(), o.nx, o.grading);
  const auto ys = cored ? cored_axis(-o.length / 2, o.length / 2, o.focus.y(), o.ny, o.core_cells, o.core_half_width)
                        : axis(-o.length / 2, o.length / 2, o.focus.y(), o.ny, o.grading);
  std::vector<double> zs;  // from the bottom up, finest at the top
  const auto depths = cored ? cored_offsets(o.core_cells, o.core_half_width, o.nz - o.core_cells, o.height)
                            : graded_offsets(o.nz, o.height, o.grading);  // below the top, increasing
  for (auto it = depths.rbegin(); it != depths.rend(); ++it) zs.push_back(-*it);
  zs.push_back(0.0);  // zs[0] = -height ... back = 0
  std::vector<Eigen::Vector3d> nodes;
  nodes.reserve(xs.size() * ys.size() * zs.size());
  for (double z : zs)
    for (double y : ys)
      for (double x : xs) nodes.emplace_back(x, y, z);
  return nodes;
}

// Elliptical square-to-disc mapping of each square ring |x|, |y| <= m about the focus onto the circle of radius m,
// blended linearly back to the identity between m = c and m = 2c (c = core half-width).
void round_the_core(const StructuredBlockOptions& o, std::vector<Eigen::Vector3d>& nodes) {
  const double c = o.core_half_width;
  for (auto& p : nodes) {
    const double x = p.x() - o.focus.x(), y = p.y() - o.focus.y();
    const double r = std::max(std::abs(x), std::abs(y));
    if (r <= 0 || r >= 2 * c) continue;
    const double xd = x * std::sqrt(1 - 0.5 * (y / r) * (y / r)), yd = y * std::sqrt(1 - 0.5 * (x / r) * (x / r));
    const double w = std::clamp((r - c) / c, 0.0, 1.0);
    p.x() = o.focus.x() + (1 - w) * xd + w * x;
    p.y() = o.focus.y() + (1 - w) * yd + w * y;
  }
}

// Each hexahedron (corners v0..v7, bottom face first) cut into 6 tetrahedra (Kuhn) or 5 (alternating with the
// parity of i + j + k so that neighbouring cells' face diagonals conform), every one positively oriented.
void add_hex_tetrahedra(const std::array<int, 8>& v, int parity, int tets_per_hex, TetMesh& m) {
  auto add = [&](std::array<int, 4> t) {
    const auto& p = m.nodes;
    const double volume = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]);
    if (volume < 0) std::swap(t[2], t[3]);
    m.tets.push_back(t);
  };
  if (tets_per_hex == 6) {
    // Kuhn subdivision along the diagonal v0-v6: conforming for any hex arrangement.
    add({v[0], v[1], v[2], v[6]});
    add({v[0], v[2], v[3], v[6]});
    add({v[0], v[3], v[7], v[6]});
    add({v[0], v[7], v[4], v[6]});
    add({v[0], v[4], v[5], v[6]});
    add({v[0], v[5], v[1], v[6]});
  } else if (parity == 0) {
    add({v[1], v[0], v[2], v[5]});
    add({v[3], v[2], v[0], v[7]});
    add({v[4], v[5], v[7], v[0]});
    add({v[6], v[7], v[5], v[2]});
    add({v[0], v[2], v[5], v[7]});
  } else {
    add({v[0], v[1], v[3], v[4]});
    add({v[2], v[3], v[1], v[6]});
    add({v[5], v[4], v[6], v[1]});
    add({v[7], v[6], v[4], v[3]});
    add({v[1], v[3], v[4], v[6]});
  }
}

}  // namespace

TetMesh structured_block_mesh(const StructuredBlockOptions& o) {
  validate(o);
  TetMesh m;
  m.nodes = grid_nodes(o);
  if (o.core_cells > 0 && o.round_core) round_the_core(o, m.nodes);
  const int px = o.nx + 1, py = o.ny + 1;
  auto id = [&](int i, int j, int k) { return i + px * (j + py * k); };
  for (int k = 0; k < o.nz; ++k)
    for (int j = 0; j < o.ny; ++j)
      for (int i = 0; i < o.nx; ++i) {
        const std::array<int, 8> v = {id(i, j, k),         id(i + 1, j, k),         id(i + 1, j + 1, k),
                                      id(i, j + 1, k),     id(i, j, k + 1),         id(i + 1, j, k + 1),
                                      id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        add_hex_tetrahedra(v, (i + j + k) % 2, o.tets_per_hex, m);
      }
  m.tet_layer.assign(m.tets.size(), 0);
  TissueLayer layer = o.material;
  layer.thickness = o.height;
  m.layers = {layer};
  return m;
}

}  // namespace needlekit::mesh
