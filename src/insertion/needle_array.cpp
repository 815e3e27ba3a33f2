#include "needlekit/insertion/needle_array.hpp"

#include <fmt/format.h>

#include <cmath>

#include "needlekit/core/errors.hpp"

namespace needlekit::insertion {
namespace {

bool hexagonal_shift(const NeedleArray& a) { return a.layout == ArrayLayout::Hexagonal && a.rows > 1; }

// m: the distance between neighbouring rows.
double row_spacing(const NeedleArray& a) {
  return a.layout == ArrayLayout::Hexagonal ? a.pitch * std::sqrt(3.0) / 2 : a.pitch;
}

}  // namespace

mesh::CellLattice cell_lattice(const NeedleArray& a) {
  return a.layout == ArrayLayout::Square ? mesh::square_lattice(a.pitch) : mesh::hexagonal_lattice(a.pitch);
}

std::vector<Eigen::Vector2d> array_positions(const NeedleArray& a) {
  // Odd rows of a hexagonal array are shifted by half a pitch; the bounding box stays centred.
  const double shift = hexagonal_shift(a) ? a.pitch / 2 : 0.0;
  std::vector<Eigen::Vector2d> positions;
  positions.reserve(static_cast<std::size_t>(a.rows) * a.columns);
  for (int row = 0; row < a.rows; ++row) {
    for (int column = 0; column < a.columns; ++column) {
      const double x = (column - 0.5 * (a.columns - 1)) * a.pitch + (row % 2 == 1 ? shift : 0.0) - shift / 2;
      const double y = (row - 0.5 * (a.rows - 1)) * row_spacing(a);
      positions.emplace_back(x, y);
    }
  }
  return positions;
}

Eigen::Vector2d array_footprint(const NeedleArray& a, double base_diameter) {
  const double shift = hexagonal_shift(a) ? a.pitch / 2 : 0.0;
  return {(a.columns - 1) * a.pitch + shift + base_diameter, (a.rows - 1) * row_spacing(a) + base_diameter};
}

void validate(const NeedleArray& a, double base_diameter) {
  for (const auto& parameter : kArrayCounts) {
    const int value = a.*parameter.field;
    if (!parameter.accepts(value)) {
      throw InvalidInput(fmt::format("array.{}: {} is out of range, expected an integer {}", parameter.key, value,
                                     parameter.range()));
    }
  }
  for (const auto& parameter : kArrayLengths) {
    const double value = a.*parameter.field;
    if (!parameter.accepts(value)) {
      throw InvalidInput(fmt::format("array.{}: {:g} um is out of range, expected a length {} m", parameter.key,
                                     value * 1e6, parameter.range()));
    }
  }
  if (a.rows * a.columns > 1 && a.pitch < base_diameter) {
    throw InvalidInput(fmt::format("array.pitch: {:g} um is smaller than the needle's base diameter {:g} um: "
                                   "neighbouring needles would overlap, expected a pitch >= {:g} um",
                                   a.pitch * 1e6, base_diameter * 1e6, base_diameter * 1e6));
  }
  if (a.layout == ArrayLayout::Hexagonal && a.rows > 1) {
    if (a.symmetry == ArraySymmetry::Quarter) {
      throw InvalidInput("array.symmetry: \"quarter\" on a hexagonal array, whose shifted rows are not mirror "
                         "symmetric about the centre line x = 0, expected \"half\" (odd rows) or \"none\"");
    }
    if (a.symmetry == ArraySymmetry::Half && a.rows % 2 == 0) {
      throw InvalidInput(fmt::format("array.symmetry: \"half\" on a hexagonal array of {} rows: with an even number "
                                     "of rows the first (unshifted) row mirrors onto the last (shifted) one, expected "
                                     "an odd number of rows or symmetry = \"none\"",
                                     a.rows));
    }
  }
}

}  // namespace needlekit::insertion
