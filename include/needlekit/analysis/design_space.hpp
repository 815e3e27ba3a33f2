// A design space for the optimizer (dissertation §4.8, Fig 6.20): inclusive grids of n, D1, D2, D3, w and L for one
// needle type, and the evaluation of one grid point's performance index with the needle-only part memoized.
#pragma once
#include <cstdint>
#include <vector>

#include "needlekit/analysis/performance_index.hpp"

namespace needlekit::analysis {

// An inclusive grid min, min + step, ..., <= max (a relative tolerance of 1e-9·step absorbs rounding).
struct GridRange {
  double min = 0;
  double max = 0;
  double step = 1;
};
// Throws InvalidInput naming `key` for non-finite values, step <= 0 or max < min (an empty range).
std::vector<double> grid_values(const GridRange& range, std::string_view key);
std::uint64_t grid_count(const GridRange& range, std::string_view key);

struct DesignSpace {
  needle::Shape shape = needle::Shape::Cone;
  bool hollow = false;
  materials::NeedleMaterial material;
  InsertionConditions conditions;   // tissue and target depth; the optimizer inserts perpendicularly (θ = 0)
  double spacing_factor = 3.0;      // β of w >= β·n·D2
  GridRange needles_per_row{5, 25, 1};
  GridRange tip_diameter{30e-6, 150e-6, 10e-6};
  GridRange base_diameter{30e-6, 300e-6, 10e-6};
  GridRange bore_diameter{20e-6, 50e-6, 10e-6};  // ignored for solid needles
  GridRange width{5000e-6, 10000e-6, 1000e-6};
  GridRange length{300e-6, 500e-6, 50e-6};
};

// The Fig 6.20 grid (notes: Table 6.3 is reproduced with these ranges, not Table 6.2's) for one needle type, in
// silicon, skin, T = 50 µm, β = 3.
DesignSpace figure_6_20_space(needle::Shape shape, bool hollow);

// Number of grid points of the space (with the shape's own dimensions: no D3 for solid needles, D2 = D1 for
// cylinders). Throws InvalidInput for invalid ranges.
std::uint64_t design_space_size(const DesignSpace& space);

}  // namespace needlekit::analysis
