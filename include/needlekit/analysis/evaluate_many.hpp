// The performance index of many needle arrays at once (for Python's needlekit.evaluate_many, Monte Carlo samples and
// design sweeps): one row per design in columns, every quantity of performance_index() out in columns, evaluated in
// parallel into preallocated output. Each row is exactly performance_index() of that design (same code, same bits);
// the tapered-column factor m (Eq 2.36), the one expensive part, is computed once per distinct section
// (shape, D1, D2, D3), since it does not depend on L or E (tapered_column_factor()).
#pragma once
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "needlekit/analysis/performance_index.hpp"

namespace needlekit::analysis {

// One entry per design; a column of size 1 applies to every design. SI units.
struct DesignColumns {
  std::span<const std::uint8_t> shape;            // static_cast<std::uint8_t>(needle::Shape)
  std::span<const std::int64_t> needles_per_row;  // n >= 1
  std::span<const double> tip_diameter;           // m, D1
  std::span<const double> base_diameter;          // m, D2
  std::span<const double> bore_diameter;          // m, D3 (0: solid)
  std::span<const double> length;                 // m, L
  std::span<const double> width;                  // m, w
  std::span<const double> angle;                  // rad, θ
  std::span<const double> target_depth;           // m, T
};

// What every design shares.
struct SharedInputs {
  materials::NeedleMaterial material;
  PunctureModel tissue = skin_puncture_model();
  PerformanceIndexOptions options;
};

// A real-valued output column: its name (the field of PerformanceIndexResult), its SI unit ("" for a number) and
// how it is read from a result (NaN where the quantity was not assessed).
struct ResultColumn {
  std::string_view name;
  std::string_view unit;
  double (*value)(const PerformanceIndexResult&);
};
// The real-valued columns of evaluate_many, in output order (declared once: the Python module names its arrays and
// docstrings from it).
std::span<const ResultColumn> result_columns();

struct ManyResults {
  std::size_t size = 0;
  std::vector<std::vector<double>> values;    // values[c][i]: result_columns()[c] of design i
  std::vector<std::uint8_t> status;           // PerformanceStatus
  std::vector<std::uint8_t> failed_checks;    // PerformanceIndexResult::failed_checks (the reason code)
  std::vector<std::uint8_t> buckling_method;  // BucklingMethod
  std::vector<std::int8_t> bending_ok;        // ω: 1, 0, or −1 when not assessed
  std::vector<std::uint8_t> small_tip_branch;
  std::uint64_t distinct_sections = 0;        // sections whose m was computed
};

// Throws InvalidInput naming the column and the row ("tip_diameter[17]: ...") for columns of different sizes (other
// than 1), a non-finite value, an unknown shape code, and for a design that performance_index() refuses (the first
// such row); then no result is returned.
ManyResults evaluate_many(const DesignColumns& designs, const SharedInputs& shared);

}  // namespace needlekit::analysis
