#include "mirrored_cell.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <utility>

namespace needlekit::mesh::detail {
namespace {

constexpr double kPlaneTolerance = 1e-9;  // of the pitch: a node on a mirror plane

// Equal margins, or none on one side (a symmetry plane of a reduced model); with sites on the corners, none or at
// least half a pitch (the margin beyond a needle holds the half of its cell beyond it).
bool mirrorable_margins(double low, double high, double pitch, bool sites_on_corners) {
  const double margin = std::max(low, high);
  return (low == 0 || high == 0 || std::abs(low - high) <= kPlaneTolerance * pitch) &&
         (!sites_on_corners || margin == 0 || margin >= 0.5 * pitch);
}

// One image of the quadrant: (x, y) -> (offset_x + sign_x x, offset_y + sign_y y), z kept.
struct Image {
  double offset_x = 0, offset_y = 0;
  int sign_x = 1, sign_y = 1;
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const {
    return {offset_x + sign_x * p.x(), offset_y + sign_y * p.y(), p.z()};
  }
};

// The nodes of the assembled cell, one per position. Images share only nodes on the mirror planes, which the
// quadrant has exactly on x = 0, x = pitch_x/2, y = 0, y = pitch_y/2, so that their images coincide bit for bit:
// an exact match of coordinates (with -0 taken as 0), not a distance tolerance.
class NodeWelder {
public:
  int add(Eigen::Vector3d p, std::vector<Eigen::Vector3d>& nodes) {
    std::array<std::uint64_t, 3> key{};
    for (int k = 0; k < 3; ++k) {
      if (p[k] == 0) p[k] = 0;  // -0 -> +0
      std::memcpy(&key[static_cast<std::size_t>(k)], &p[k], sizeof(double));
    }
    const auto [it, inserted] = index_.try_emplace(key, static_cast<int>(nodes.size()));
    if (inserted) nodes.push_back(p);
    return it->second;
  }

private:
  std::map<std::array<std::uint64_t, 3>, int> index_;
};

}  // namespace

bool mirrors_from_a_quadrant(const CellLayout& layout, const LayeredBlockOptions& options) {
  const bool one_central_site =
      layout.sites.size() == 1 && layout.sites.front().norm() <= kPlaneTolerance * layout.pitch_x;
  return (one_central_site || layout.sites_on_corners) && layout.top_row_sites.empty() &&
         options.site_circle_radius == 0 &&
         mirrorable_margins(layout.margin_left, layout.margin_right, layout.pitch_x, layout.sites_on_corners) &&
         mirrorable_margins(layout.margin_bottom, layout.margin_top, layout.pitch_y, layout.sites_on_corners);
}

CellBlockMesh mirrored_cell(const CellBlockMesh& quadrant, const CellLayout& layout) {
  const TetMesh& q = quadrant.mesh;
  const double half_x = 0.5 * layout.pitch_x, half_y = 0.5 * layout.pitch_y;
  // The quadrant's nodes put exactly on its planes.
  std::vector<Eigen::Vector3d> nodes = q.nodes;
  for (Eigen::Vector3d& p : nodes) {
    for (const auto& [axis, plane, pitch] :
         {std::tuple{0, 0.0, layout.pitch_x}, std::tuple{0, half_x, layout.pitch_x}, std::tuple{1, 0.0, layout.pitch_y},
          std::tuple{1, half_y, layout.pitch_y}}) {
      if (std::abs(p[axis] - plane) <= kPlaneTolerance * pitch) p[axis] = plane;
    }
  }
  // The cell's quadrant x, y >= 0 as images of the quadrant, each with the piece it fills (-1: outside). A site at
  // the cell's centre: the quadrant itself. Sites on the corners: the needle at (pitch_x/2, pitch_y/2) has the
  // quadrant turned by a half turn on its -x, -y side (the cell, piece 1) and the quadrant's mirror images on its
  // other sides, with the margins beyond them (the margin pieces: the half of the needle's cell beyond it, then the
  // margin of a centred cell).
  struct PlacedImage {
    Image image;
    int piece_of[9];  // the cell's piece for each of the quadrant's pieces
  };
  std::vector<PlacedImage> quarter;
  if (!layout.sites_on_corners) {
    quarter.push_back({Image{}, {-1, -1, -1, -1, 4, 5, -1, 7, 8}});
  } else {
    for (int sx : {-1, 1}) {
      for (int sy : {-1, 1}) {
        PlacedImage placed{Image{half_x, half_y, sx, sy}, {-1, -1, -1, -1, -1, -1, -1, -1, -1}};
        for (int k : {4, 5, 7, 8}) {
          const int kx = k % 3, ky = k / 3;  // 1 the quadrant, 2 its margin
          if ((sx < 0 && kx == 2) || (sy < 0 && ky == 2)) continue;  // would fall outside the cell's quadrant
          placed.piece_of[k] = 3 * (sy > 0 ? 2 : 1) + (sx > 0 ? 2 : 1);
        }
        quarter.push_back(placed);
      }
    }
  }
  const bool margin[2][2] = {{layout.margin_left > 0, layout.margin_right > 0},
                             {layout.margin_bottom > 0, layout.margin_top > 0}};
  CellBlockMesh cell;
  cell.mesh.layers = q.layers;
  NodeWelder welder;
  for (int mx : {1, -1}) {
    for (int my : {1, -1}) {  // the cell's quadrant mirrored across x = 0 and y = 0
      for (const PlacedImage& placed : quarter) {
        const Image image{mx * placed.image.offset_x, my * placed.image.offset_y, mx * placed.image.sign_x,
                          my * placed.image.sign_y};
        std::vector<int> node_of(nodes.size(), -1);
        for (std::size_t t = 0; t < q.tets.size(); ++t) {
          const int k = placed.piece_of[quadrant.piece[t]];
          if (k < 0) continue;
          const int px = mx > 0 ? k % 3 : 2 - k % 3, py = my > 0 ? k / 3 : 2 - k / 3;
          if ((px != 1 && !margin[0][px / 2]) || (py != 1 && !margin[1][py / 2])) continue;
          std::array<int, 4> tet{};
          for (std::size_t a = 0; a < 4; ++a) {
            const auto n = static_cast<std::size_t>(q.tets[t][a]);
            if (node_of[n] < 0) node_of[n] = welder.add(image(nodes[n]), cell.mesh.nodes);
            tet[a] = node_of[n];
          }
          if (image.sign_x * image.sign_y < 0) std::swap(tet[0], tet[1]);  // a reflection reverses the orientation
          cell.mesh.tets.push_back(tet);
          cell.mesh.tet_layer.push_back(q.tet_layer[t]);
          cell.piece.push_back(3 * py + px);
        }
      }
    }
  }
  return cell;
}

}  // namespace needlekit::mesh::detail
