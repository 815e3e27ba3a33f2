// A microneedle array (a patch): one needle repeated on a square or hexagonal grid of a given pitch, all needles
// moving together (the patch's rigid base), and the reduced models that its mirror symmetry allows (issue 36).
//
// Frame. The array is centred on the origin of the tissue frame: its footprint, the bounding box of the needles'
// bases, is centred on (0, 0). Needle k = row * columns + column, row 0 at the smallest y, column 0 at the smallest x.
//
// Symmetry. "half" solves the half y >= 0 of the block with u_y = 0 on the plane y = 0 (the centre line between
// the rows); "quarter" the quarter x >= 0, y >= 0 with u_x = 0 and u_y = 0 on both centre lines. A needle on a plane
// is cut by it: the reduced model carries half (a quarter on both planes) of its force, and the whole array's forces
// are the reduced ones multiplied back (fem::BoundaryCondition::HalfSymmetry / QuarterSymmetry).
#pragma once
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/parameter.hpp"
#include "needlekit/mesh/cell_replication.hpp"

namespace needlekit::insertion {

enum class ArrayLayout { Square, Hexagonal };
inline constexpr EnumTable<ArrayLayout, 2> kArrayLayoutNames{{
    {ArrayLayout::Square, "square", "rows and columns a pitch apart"},
    {ArrayLayout::Hexagonal, "hexagonal",
     "every other row shifted by half a pitch, rows pitch*sqrt(3)/2 apart: each needle a pitch from six neighbours"},
}};

enum class ArraySymmetry { None, Half, Quarter };
inline constexpr EnumTable<ArraySymmetry, 3> kArraySymmetryNames{{
    {ArraySymmetry::None, "none", "the whole array is solved"},
    {ArraySymmetry::Half, "half",
     "the half y >= 0, a symmetry plane through the centre line between the rows (square; hexagonal with odd rows)"},
    {ArraySymmetry::Quarter, "quarter", "the quarter x >= 0, y >= 0, symmetry planes through both centre lines (square)"},
}};

struct NeedleArray {
  ArrayLayout layout = ArrayLayout::Square;
  int rows = 1;              // [1, kMaxArraySide]: needles along y
  int columns = 1;           // [1, kMaxArraySide]: needles along x
  double pitch = 600e-6;     // m, > 0: centre distance of neighbouring needles (at least the needle's base diameter)
  double margin = 1000e-6;   // m, >= 0: tissue beyond the footprint on every side when the block's size is not given
  bool backing_plate = false;  // a rigid plate at the needles' base (the patch): its travel and force are reported
  ArraySymmetry symmetry = ArraySymmetry::None;
};

inline constexpr double kMaxArraySide = 100;  // rows and columns: a 100 x 100 patch
inline constexpr Parameter<NeedleArray, int> kArrayCounts[] = {
    {"rows", &NeedleArray::rows, 1, kMaxArraySide, Bound::Closed, Bound::Closed, "needles along y"},
    {"columns", &NeedleArray::columns, 1, kMaxArraySide, Bound::Closed, Bound::Closed, "needles along x"},
};
inline constexpr Parameter<NeedleArray, double> kArrayLengths[] = {
    {"pitch", &NeedleArray::pitch, 0, kNoLimit, Bound::Open, Bound::Open,
     "centre distance of neighbouring needles, at least the needle's base diameter"},
    {"margin", &NeedleArray::margin, 0, kNoLimit, Bound::Closed, Bound::Open,
     "tissue beyond the array's footprint on every side, when [tissue] width/length are not given"},
};

// m: the (x, y) of every needle's tip centre, needle k = row * columns + column.
std::vector<Eigen::Vector2d> array_positions(const NeedleArray& array);

// The cell the array's block repeats (mesh/cell_replication.hpp): a needle's square, or a hexagonal array's pair of
// rows.
mesh::CellLattice cell_lattice(const NeedleArray& array);

// m: the footprint's extent in x and y, the bounding box of the needles' bases: (columns - 1) * pitch + base diameter
// by (rows - 1) * pitch + base diameter for a square array.
Eigen::Vector2d array_footprint(const NeedleArray& array, double base_diameter);

// Throws InvalidInput naming the key ("array.pitch: ..."): counts or lengths out of range, a pitch below the needle's
// base diameter (neighbouring needles would overlap), a symmetry the layout does not have (hexagonal with "quarter",
// or "half" with an even number of rows: the shifted rows do not mirror onto each other).
void validate(const NeedleArray& array, double base_diameter);

}  // namespace needlekit::insertion
