// An array block's repeating cell with the Gmsh C++ API: one OpenCASCADE box per piece (the -x margin, the cell, the
// +x margin, times the same in y) and layer, fragmented so that every piece and layer interface is conforming; the
// sites (and their circles) embedded in the cell's top face (a hexagonal array's odd last row in the +y margin
// strip's); the cell's +x side faces set as periodic copies of its
// -x faces (gmsh::model::mesh::setPeriodic with a translation by pitch_x), and +y of -y (by pitch_y), in every row of
// pieces and every layer, so that translated copies of the cell match node for node (cell_replication.hpp assembles
// them).
// The size field is the whole block's with the cell's sites. A square cell is its site's Voronoi cell and a margin
// piece lies beyond its row or column, so the nearest needle is always the cell's own and the field of the assembled
// array equals the whole-block mesher's there. A hexagonal cell (two sites) is not: near its sides the nearest needle
// can be a neighbouring cell's, so the field also takes the sites' copies in the eight neighbouring cells (points
// that are not part of the model's volumes). Beyond the array's edge those copies stand for needles that do not
// exist, and the margins are refined around them too: finer than needed, never coarser.
// A cell that is its own mirror image (CellLayout::quadrant) is meshed as its quadrant x, y >= 0 with the margin
// pieces beyond it, and mirrored by the library (mirrored_cell.hpp).
// Part of the Gmsh module; the layout is checked by layered_block_mesh (src/mesh/layered_block_mesh.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "block_meshing_steps.hpp"
#include "gmsh_functions.hpp"
#include "gmsh_session.hpp"

namespace needlekit::mesh::detail {
namespace {

constexpr int kGmshTet4 = 4;

// One extent of a piece along x or y (model units) and its index: 0 the -side margin, 1 the cell, 2 the +side one.
struct Segment {
  double low = 0, high = 0;
  int index = 0;
};

std::vector<Segment> segments(double pitch, double margin_low, double margin_high) {  // pitch: along this axis
  std::vector<Segment> result;
  if (margin_low > 0) result.push_back({-0.5 * pitch - margin_low, -0.5 * pitch, 0});
  result.push_back({-0.5 * pitch, 0.5 * pitch, 1});
  if (margin_high > 0) result.push_back({0.5 * pitch, 0.5 * pitch + margin_high, 2});
  return result;
}

// A quadrant's extents along one axis (CellLayout::quadrant): [0, pitch/2] and the margin beyond it, rounded to 1e-6
// model units so that a full model and a reduced one through a row of needles (whose margin beyond the needles is
// half a pitch wider) mesh the same Gmsh model: Gmsh's 3D Delaunay meshes all volumes at once, so the quadrant's mesh
// depends on every piece beside it.
std::vector<Segment> quadrant_segments(double pitch, double margin_low, double margin_high, bool sites_on_corners) {
  const double margin = std::max(margin_low, margin_high), half = 0.5 * pitch;
  const double beyond = std::max(0.0, std::round((sites_on_corners ? margin - half : margin) * 1e6) * 1e-6);
  std::vector<Segment> result{{0, half, 1}};
  if (beyond > 0) result.push_back({half, half + beyond, 2});
  return result;
}

struct PieceVolume {
  int volume = 0;
  int piece = 0;  // 3 * py + px
  int layer = 0;
};

// Boxes per piece and layer, fragmented into conforming volumes.
std::vector<PieceVolume> piece_volumes(const std::vector<Segment>& xs, const std::vector<Segment>& ys,
                                       const LayerVolumes& layers) {
  std::vector<PieceVolume> pieces;
  gmsh::vectorpair boxes;
  for (std::size_t i = 0; i < layers.tops.size(); ++i) {
    const double top = layers.tops[i], bottom = i + 1 < layers.tops.size() ? layers.tops[i + 1] : -layers.height;
    for (const Segment& y : ys) {
      for (const Segment& x : xs) {
        boxes.emplace_back(3, gmsh::model::occ::addBox(x.low, y.low, bottom, x.high - x.low, y.high - y.low, top - bottom));
        pieces.push_back({boxes.back().second, 3 * y.index + x.index, static_cast<int>(i)});
      }
    }
  }
  const std::vector<int> volumes = fragmented_volumes(boxes);
  for (std::size_t i = 0; i < pieces.size(); ++i) pieces[i].volume = volumes[i];
  return pieces;
}

// The one surface inside the box [low, high] (model units).
int face_in_box(const std::array<double, 3>& low, const std::array<double, 3>& high) {
  gmsh::vectorpair faces;
  gmsh::model::getEntitiesInBoundingBox(low[0], low[1], low[2], high[0], high[1], high[2], faces, 2);
  if (faces.size() != 1) {
    throw std::logic_error(fmt::format("{} faces in the box ({}, {}, {}) - ({}, {}, {})", faces.size(), low[0], low[1],
                                       low[2], high[0], high[1], high[2]));
  }
  return faces[0].second;
}

// The cell's faces at +pitch/2 along `axis` (0: x, 1: y) as translated copies of those at -pitch/2, one pair per
// piece across the other axis and per layer.
void set_periodic_faces(int axis, double pitch, const std::vector<Segment>& across, const LayerVolumes& layers,
                        double eps) {
  std::vector<double> translation{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  translation[axis == 0 ? 3 : 7] = pitch;
  const int other = 1 - axis;
  for (std::size_t i = 0; i < layers.tops.size(); ++i) {
    const double top = layers.tops[i], bottom = i + 1 < layers.tops.size() ? layers.tops[i + 1] : -layers.height;
    for (const Segment& s : across) {
      std::array<double, 3> low{}, high{};
      low[other] = s.low - eps, high[other] = s.high + eps;
      low[2] = bottom - eps, high[2] = top + eps;
      low[axis] = -0.5 * pitch - eps, high[axis] = -0.5 * pitch + eps;
      const int master = face_in_box(low, high);
      low[axis] += pitch, high[axis] += pitch;
      gmsh::model::mesh::setPeriodic(2, {face_in_box(low, high)}, {master}, translation);
    }
  }
}

// Sites on corners of the top face (CellLayout::sites_on_corners, or the quadrant's site): its corner vertices,
// nothing to embed.
std::vector<int> corner_site_points(const std::vector<Eigen::Vector2d>& sites, double u, double eps) {
  gmsh::model::occ::synchronize();
  std::vector<int> corners;
  for (const Eigen::Vector2d& s : sites) {
    gmsh::vectorpair vertex;
    gmsh::model::getEntitiesInBoundingBox(s.x() * u - eps, s.y() * u - eps, -eps, s.x() * u + eps, s.y() * u + eps, eps,
                                          vertex, 0);
    if (vertex.size() != 1) throw std::logic_error(fmt::format("{} vertices at a corner of the cell", vertex.size()));
    corners.push_back(vertex[0].second);
  }
  return corners;
}

// The sites (and their circles) embedded in the cell's top face, the top row's in the +y margin strip's, and, for a
// cell of several sites, their copies in the neighbouring cells as free points for the size field; returns the point
// tags for the field.
std::vector<int> cell_site_points(const LayeredBlockOptions& options, const CellLayout& layout, double u, double eps) {
  if (layout.quadrant) return corner_site_points({Eigen::Vector2d::Zero()}, u, eps);
  if (layout.sites_on_corners) return corner_site_points(layout.sites, u, eps);
  std::vector<int> sites, circles, top_row, top_row_circles, field_points;
  const auto add_site = [&](const Eigen::Vector2d& s, std::vector<int>& points, std::vector<int>& rims) {
    points.push_back(gmsh::model::occ::addPoint(s.x() * u, s.y() * u, 0));
    if (options.site_circle_radius > 0) {
      rims.push_back(gmsh::model::occ::addCircle(s.x() * u, s.y() * u, 0, options.site_circle_radius * u));
    }
  };
  for (const Eigen::Vector2d& s : layout.sites) add_site(s, sites, circles);
  for (const Eigen::Vector2d& s : layout.top_row_sites) add_site(s, top_row, top_row_circles);
  field_points = sites;
  field_points.insert(field_points.end(), top_row.begin(), top_row.end());
  if (layout.sites.size() > 1) {
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        if (i == 0 && j == 0) continue;
        for (const Eigen::Vector2d& s : layout.sites) {
          field_points.push_back(gmsh::model::occ::addPoint((s.x() + i * layout.pitch_x) * u,
                                                            (s.y() + j * layout.pitch_y) * u, 0));
        }
      }
    }
  }
  gmsh::model::occ::synchronize();
  const double hx = 0.5 * layout.pitch_x * u, hy = 0.5 * layout.pitch_y * u;
  const int top = face_in_box({-hx - eps, -hy - eps, -eps}, {hx + eps, hy + eps, eps});
  gmsh::model::mesh::embed(0, sites, 2, top);
  if (!circles.empty()) gmsh::model::mesh::embed(1, circles, 2, top);
  if (!top_row.empty()) {
    const int strip = face_in_box({-hx - eps, hy - eps, -eps}, {hx + eps, hy + layout.margin_top * u + eps, eps});
    gmsh::model::mesh::embed(0, top_row, 2, strip);
    if (!top_row_circles.empty()) gmsh::model::mesh::embed(1, top_row_circles, 2, strip);
  }
  return field_points;
}

// The tetrahedra of the pieces as a CellBlockMesh (the piece of each tetrahedron in the order gmsh_tet_mesh takes
// the volumes).
CellBlockMesh cell_tet_mesh(const std::vector<TissueLayer>& layers, const std::vector<PieceVolume>& pieces) {
  std::vector<VolumeLayer> volumes;
  for (const PieceVolume& p : pieces) volumes.push_back({p.volume, p.layer});
  CellBlockMesh result;
  result.mesh = gmsh_tet_mesh(layers, volumes);
  for (const PieceVolume& p : pieces) {
    std::vector<std::size_t> element_tags, node_tags;
    gmsh::model::mesh::getElementsByType(kGmshTet4, element_tags, node_tags, p.volume);
    result.piece.insert(result.piece.end(), element_tags.size(), p.piece);
  }
  if (result.piece.size() != result.mesh.tets.size()) throw std::logic_error("cell block: pieces do not add up");
  return result;
}

}  // namespace

CellBlockMesh gmsh_cell_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                              const CellLayout& layout) {
  const double u = 1 / kModelUnit;  // m -> model units
  const double px = layout.pitch_x * u, py = layout.pitch_y * u;
  const auto axis_segments = [&](double pitch, double margin_low, double margin_high) {
    return layout.quadrant ? quadrant_segments(pitch, margin_low * u, margin_high * u, layout.sites_on_corners)
                           : segments(pitch, margin_low * u, margin_high * u);
  };
  const std::vector<Segment> xs = axis_segments(px, layout.margin_left, layout.margin_right);
  const std::vector<Segment> ys = axis_segments(py, layout.margin_bottom, layout.margin_top);
  // The extent that holds every piece, centred on the cell (for the searches and the thin-layer boxes).
  const double w = 2 * std::max(-xs.front().low, xs.back().high), l = 2 * std::max(-ys.front().low, ys.back().high);
  CellBlockMesh result;
  GmshSession session;
  try {
    gmsh::model::add("needlekit_array_cell");
    LayerVolumes volumes;
    for (const TissueLayer& layer : layers) {
      volumes.tops.push_back(-volumes.height);
      volumes.height += layer.thickness * u;
    }
    const std::vector<PieceVolume> pieces = piece_volumes(xs, ys, volumes);
    double smallest = std::min({px, py, layers.front().thickness * u});
    for (const std::vector<Segment>* axis : {&xs, &ys}) {
      for (const Segment& s : *axis) smallest = std::min(smallest, s.high - s.low);
    }
    const double eps = 1e-3 * smallest;
    const std::vector<int> field_points = cell_site_points(options, layout, u, eps);
    if (!layout.quadrant) {
      set_periodic_faces(0, px, ys, volumes, eps);
      set_periodic_faces(1, py, xs, volumes, eps);
    }
    alternate_interface_algorithms(volumes, w, l, eps);
    set_size_fields(options, layers, volumes, field_points, w, l, u);
    set_mesh_options(0);  // one thread: the cell, and so the array, is the same in every run
    gmsh::model::mesh::generate(3);
    result = cell_tet_mesh(layers, pieces);
  } catch (...) {
    throw std::runtime_error(fmt::format("array cell: Gmsh failed: {}", gmsh_error_message()));
  }
  return result;
}

}  // namespace needlekit::mesh::detail
