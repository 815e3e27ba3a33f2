#include "needlekit/analysis/evaluate_many.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <mutex>
#include <unordered_map>

#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {
namespace {

constexpr double kNotAssessed = std::numeric_limits<double>::quiet_NaN();

constexpr std::array<ResultColumn, 21> kColumns{{
    {"tip_area", "m^2", [](const PerformanceIndexResult& r) { return r.tip_area; }},
    {"puncture_force", "N", [](const PerformanceIndexResult& r) { return r.puncture_force; }},
    {"deformation", "m", [](const PerformanceIndexResult& r) { return r.deformation; }},
    {"cutting_depth", "m", [](const PerformanceIndexResult& r) { return r.cutting_depth; }},
    {"permeation_depth", "m", [](const PerformanceIndexResult& r) { return r.permeation_depth; }},
    {"diameter_at_surface", "m", [](const PerformanceIndexResult& r) { return r.diameter_at_surface; }},
    {"embedded_volume", "m^3", [](const PerformanceIndexResult& r) { return r.embedded_volume; }},
    {"q_factor", "m^2", [](const PerformanceIndexResult& r) { return r.q_factor; }},
    {"hole_volume", "m^3", [](const PerformanceIndexResult& r) { return r.hole_volume; }},
    {"gap_volume", "m^3", [](const PerformanceIndexResult& r) { return r.gap_volume; }},
    {"pitch", "m", [](const PerformanceIndexResult& r) { return r.pitch; }},
    {"fractional_skin_volume", "", [](const PerformanceIndexResult& r) { return r.fractional_skin_volume; }},
    {"needle_volume", "m^3", [](const PerformanceIndexResult& r) { return r.needle_volume; }},
    {"critical_buckling_load", "N", [](const PerformanceIndexResult& r) { return r.buckling.critical_load; }},
    {"tapered_factor", "", [](const PerformanceIndexResult& r) { return r.buckling.tapered_factor; }},
    {"slenderness_ratio", "", [](const PerformanceIndexResult& r) { return r.buckling.slenderness_ratio; }},
    {"column_constant", "",
     [](const PerformanceIndexResult& r) {
       return r.buckling.column_constant > 0 ? r.buckling.column_constant : kNotAssessed;
     }},
    {"buckling_force", "N", [](const PerformanceIndexResult& r) { return r.buckling_force; }},
    {"critical_bending_load", "N",
     [](const PerformanceIndexResult& r) { return r.critical_bending_load.value_or(kNotAssessed); }},
    {"bending_force", "N", [](const PerformanceIndexResult& r) { return r.bending_force; }},
    {"performance_index", "1/m", [](const PerformanceIndexResult& r) { return r.performance_index; }},
}};

template <class T>
T at(std::span<const T> column, std::size_t row) {
  return column.size() == 1 ? column[0] : column[row];
}

struct Section {
  std::uint8_t shape;
  double d1, d2, d3;
  bool operator==(const Section&) const = default;
};
struct SectionHash {
  std::size_t operator()(const Section& s) const {
    std::size_t h = s.shape;
    for (double v : {s.d1, s.d2, s.d3}) h = h * 1000003u ^ std::hash<std::uint64_t>{}(std::bit_cast<std::uint64_t>(v));
    return h;
  }
};

// The number of designs: every column has this size or size 1.
std::size_t row_count(const DesignColumns& d) {
  const std::array<std::pair<std::string_view, std::size_t>, 9> sizes{{{"shape", d.shape.size()},
                                                                       {"needles_per_row", d.needles_per_row.size()},
                                                                       {"tip_diameter", d.tip_diameter.size()},
                                                                       {"base_diameter", d.base_diameter.size()},
                                                                       {"bore_diameter", d.bore_diameter.size()},
                                                                       {"length", d.length.size()},
                                                                       {"width", d.width.size()},
                                                                       {"angle", d.angle.size()},
                                                                       {"target_depth", d.target_depth.size()}}};
  std::size_t rows = 1;
  for (const auto& [name, size] : sizes) {
    if (size != 1) rows = size;
  }
  for (const auto& [name, size] : sizes) {
    if (size != 1 && size != rows) {
      throw InvalidInput(
          fmt::format("{}: {} values, but other columns have {} (every column has one value per design, "
                      "or a single value for all)",
                      name, size, rows));
    }
  }
  return rows;
}

void check_finite(std::span<const double> column, std::string_view name) {
  for (std::size_t i = 0; i < column.size(); ++i) {
    if (!std::isfinite(column[i])) {
      throw InvalidInput(fmt::format("{}[{}]: {} is not a finite number", name, i, column[i]));
    }
  }
}

void check_columns(const DesignColumns& d) {
  for (std::size_t i = 0; i < d.shape.size(); ++i) {
    if (d.shape[i] > static_cast<std::uint8_t>(needle::Shape::Bevel)) {
      throw InvalidInput(fmt::format("shape[{}]: code {} is not a shape, expected 0 (cylinder), 1 (cone) or 2 (bevel)",
                                     i, d.shape[i]));
    }
  }
  check_finite(d.tip_diameter, "tip_diameter");
  check_finite(d.base_diameter, "base_diameter");
  check_finite(d.bore_diameter, "bore_diameter");
  check_finite(d.length, "length");
  check_finite(d.width, "width");
  check_finite(d.angle, "angle");
  check_finite(d.target_depth, "target_depth");
  for (std::size_t i = 0; i < d.needles_per_row.size(); ++i) {
    if (d.needles_per_row[i] < 1 || d.needles_per_row[i] > std::numeric_limits<int>::max()) {
      throw InvalidInput(fmt::format("needles_per_row[{}]: {} must be >= 1", i, d.needles_per_row[i]));
    }
  }
}

needle::NeedleGeometry needle_at(const DesignColumns& d, std::size_t row) {
  return {static_cast<needle::Shape>(at(d.shape, row)), at(d.tip_diameter, row), at(d.base_diameter, row),
          at(d.bore_diameter, row), at(d.length, row)};
}

}  // namespace

std::span<const ResultColumn> result_columns() { return kColumns; }

ManyResults evaluate_many(const DesignColumns& designs, const SharedInputs& shared) {
  const std::size_t rows = row_count(designs);
  check_columns(designs);
  materials::validate(shared.material, "material");
  validate(shared.tissue, "tissue");

  // m of every distinct tapered section, computed in parallel (NaN for a section performance_index() will refuse).
  std::unordered_map<Section, std::size_t, SectionHash> section_index;
  std::vector<std::size_t> row_section(rows, 0);
  std::vector<Section> sections;
  for (std::size_t i = 0; i < rows; ++i) {
    const std::uint8_t shape = at(designs.shape, i);
    if (shape == static_cast<std::uint8_t>(needle::Shape::Cylinder)) continue;
    const Section key{shape, at(designs.tip_diameter, i), at(designs.base_diameter, i), at(designs.bore_diameter, i)};
    const auto [slot, added] = section_index.try_emplace(key, sections.size());
    if (added) sections.push_back(key);
    row_section[i] = slot->second;
  }
  std::vector<double> factor(sections.size());
  tbb::parallel_for(std::size_t{0}, sections.size(), [&](std::size_t s) {
    const needle::NeedleGeometry section{static_cast<needle::Shape>(sections[s].shape), sections[s].d1, sections[s].d2,
                                         sections[s].d3, 1.0};
    try {
      needle::validate(section);
      factor[s] = tapered_column_factor(section, shared.options.buckling.end_condition);
    } catch (const InvalidInput&) {
      factor[s] = std::numeric_limits<double>::quiet_NaN();
    }
  });

  PerformanceIndexOptions options = shared.options;
  options.explain = false;  // numbers and codes only: no messages to format per design
  ManyResults out;
  out.size = rows;
  out.distinct_sections = sections.size();
  out.values.assign(kColumns.size(), std::vector<double>(rows));
  out.status.resize(rows);
  out.failed_checks.resize(rows);
  out.buckling_method.resize(rows);
  out.bending_ok.resize(rows);
  out.small_tip_branch.resize(rows);

  std::mutex error_mutex;
  std::size_t error_row = rows;
  std::string error_message;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows), [&](const tbb::blocked_range<std::size_t>& range) {
    ArrayDesign design;
    design.material = shared.material;
    InsertionConditions conditions;
    conditions.tissue = shared.tissue;
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      design.needle = needle_at(designs, i);
      design.needles_per_row = static_cast<int>(at(designs.needles_per_row, i));
      design.width = at(designs.width, i);
      conditions.angle = at(designs.angle, i);
      conditions.target_depth = at(designs.target_depth, i);
      const bool tapered = design.needle.shape != needle::Shape::Cylinder;
      try {
        const PerformanceIndexResult r = performance_index(
            design, conditions, options, tapered ? std::optional<double>(factor[row_section[i]]) : std::nullopt);
        for (std::size_t c = 0; c < kColumns.size(); ++c) out.values[c][i] = kColumns[c].value(r);
        out.status[i] = static_cast<std::uint8_t>(r.status);
        out.failed_checks[i] = static_cast<std::uint8_t>(r.failed_checks);
        out.buckling_method[i] = static_cast<std::uint8_t>(r.buckling.method);
        out.bending_ok[i] = r.bending_ok ? static_cast<std::int8_t>(*r.bending_ok) : std::int8_t{-1};
        out.small_tip_branch[i] = r.small_tip_branch;
      } catch (const InvalidInput& error) {
        const std::lock_guard lock(error_mutex);
        if (i < error_row) {
          error_row = i;
          error_message = error.what();
        }
      }
    }
  });
  if (error_row < rows) throw InvalidInput(fmt::format("design [{}]: {}", error_row, error_message));
  return out;
}

}  // namespace needlekit::analysis
