// The Flexi-patch (dissertation §5.5, Figs 5.6, 5.7): n_h × n_v mass nodes on a flat substrate joined by the
// eight-neighbour springs of Fig 5.6 (structural springs along U and V, shear springs along both diagonals), a
// spring constant per direction (isotropic or anisotropic), inner nodes (eight neighbours) and outer nodes (fewer),
// and one needle of the same shape, length and material at every node, pointing against the node normal.
// A rigid patch is the same grid moved as one rigid body.
#pragma once
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::patch {

enum class SpringDirection {
  U,             // structural, N(i,j)–N(i+1,j)
  V,             // structural, N(i,j)–N(i,j+1)
  Diagonal,      // shear, N(i,j)–N(i+1,j+1)
  AntiDiagonal,  // shear, N(i+1,j)–N(i,j+1)
};
inline constexpr EnumTable<SpringDirection, 4> kSpringDirectionNames{{
    {SpringDirection::U, "u", "structural, N(i,j)-N(i+1,j)"},
    {SpringDirection::V, "v", "structural, N(i,j)-N(i,j+1)"},
    {SpringDirection::Diagonal, "diagonal", "shear, N(i,j)-N(i+1,j+1)"},
    {SpringDirection::AntiDiagonal, "anti-diagonal", "shear, N(i+1,j)-N(i,j+1)"},
}};
std::string_view to_string(SpringDirection direction);

struct Spring {
  int a = 0, b = 0;            // node indices
  SpringDirection direction = SpringDirection::U;
  double rest_length = 0;      // m, L^{t=0} of Eq 5.14
  double stiffness = 0;        // N/m, K of Eq 5.13
};

struct PatchDesignOptions {
  int needles_u = 10;            // n_h, needles (= nodes) along U, [2, 10000]
  int needles_v = 10;            // n_v, needles along V, [2, 10000]
  double width_u = 10e-3;        // m, (0, inf): patch side w along U; node pitch Pxy = w/n (Eq 4.25), nodes at the
                                 // centres of the n cells, so the outermost nodes are w/(2n) inside the edge
  double width_v = 10e-3;        // m, (0, inf): patch side along V
  double stiffness_u = 1e3;      // N/m, (0, inf): spring constant along U (§6.4: 1 N/mm)
  double stiffness_v = 1e3;      // N/m, (0, inf): spring constant along V
  double stiffness_diagonal = 1e3;  // N/m, (0, inf): spring constant of both diagonals (isotropic: all equal)
  needle::NeedleGeometry needle;    // the needle at every node (validated)
  materials::NeedleMaterial material;
};

struct PatchDesign {
  int nodes_u = 0, nodes_v = 0;
  double pitch_u = 0, pitch_v = 0;            // m, w/n
  double width_u = 0, width_v = 0;            // m
  std::vector<Eigen::Vector2d> rest_positions;  // m, (u, v) of node i + nodes_u·j, centred on the patch centre
  std::vector<Spring> springs;
  std::vector<bool> inner;                    // true for nodes with eight neighbours (§5.5)
  needle::NeedleGeometry needle;
  materials::NeedleMaterial material;

  int node(int i, int j) const { return i + nodes_u * j; }
  int node_count() const { return nodes_u * nodes_v; }
  int column(int node) const { return node % nodes_u; }  // i
  int row(int node) const { return node / nodes_u; }     // j
};

// Builds the grid, springs and needles. Throws InvalidInput naming the field ("patch.spring_constant: ...") for a
// non-positive or non-finite size or spring constant, fewer than 2 needles per side, or an invalid needle.
PatchDesign patch_design(const PatchDesignOptions& options);

// The (up to eight) neighbours of a node (§5.5), in the order E, NE, N, NW, W, SW, S, SE.
std::vector<int> neighbors(const PatchDesign& design, int node);

}  // namespace needlekit::patch
