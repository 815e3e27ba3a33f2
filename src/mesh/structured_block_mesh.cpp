#include "needlekit/mesh/structured_block_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "needlekit/core/errors.hpp"

namespace needlekit::mesh {

namespace {

void require(bool ok, const std::string& field, double value, const std::string& expected) {
  if (!ok)
    throw InvalidInput("structured block: " + field + " = " + std::to_string(value) + ", expected " + expected);
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

}  // namespace

TetMesh structured_block_mesh(const StructuredBlockOptions& o) {
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

  const auto xs = axis(-o.width / 2, o.width / 2, o.focus.x(), o.nx, o.grading);
  const auto ys = axis(-o.length / 2, o.length / 2, o.focus.y(), o.ny, o.grading);
  std::vector<double> zs;  // from the bottom up, finest at the top
  for (double d : graded_offsets(o.nz, o.height, o.grading)) zs.push_back(-d);
  zs.push_back(0.0);
  std::reverse(zs.begin(), zs.end());  // zs[0] = -height ... back = 0

  const int px = o.nx + 1, py = o.ny + 1, pz = o.nz + 1;
  TetMesh m;
  m.nodes.reserve(static_cast<size_t>(px) * py * pz);
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j)
      for (int i = 0; i < px; ++i) m.nodes.emplace_back(xs[i], ys[j], zs[k]);
  auto id = [&](int i, int j, int k) { return i + px * (j + py * k); };

  auto add = [&](std::array<int, 4> t) {
    const auto& p = m.nodes;
    const double v = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]);
    if (v < 0) std::swap(t[2], t[3]);
    m.tets.push_back(t);
  };
  for (int k = 0; k < o.nz; ++k)
    for (int j = 0; j < o.ny; ++j)
      for (int i = 0; i < o.nx; ++i) {
        const int v[8] = {id(i, j, k),         id(i + 1, j, k),         id(i + 1, j + 1, k),
                          id(i, j + 1, k),     id(i, j, k + 1),         id(i + 1, j, k + 1),
                          id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        if (o.tets_per_hex == 6) {
          // Kuhn subdivision along the diagonal v0-v6: conforming for any hex arrangement.
          add({v[0], v[1], v[2], v[6]});
          add({v[0], v[2], v[3], v[6]});
          add({v[0], v[3], v[7], v[6]});
          add({v[0], v[7], v[4], v[6]});
          add({v[0], v[4], v[5], v[6]});
          add({v[0], v[5], v[1], v[6]});
        } else if ((i + j + k) % 2 == 0) {
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
  m.tet_layer.assign(m.tets.size(), 0);
  TissueLayer layer = o.material;
  layer.thickness = o.height;
  m.layers = {layer};
  return m;
}

}  // namespace needlekit::mesh
