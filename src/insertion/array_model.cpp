#include "array_model.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "needlekit/core/errors.hpp"

namespace needlekit::insertion {
namespace {

std::string um(double metres) { return fmt::format("{:.4g} um", metres * 1e6); }

// m: the extent of the needle mesh along axis `axis` (the needle frame: z along the needle).
double extent(const geometry::TriangleMesh& needle, int axis) {
  double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : needle.vertices) top = std::max(top, v[axis]), bottom = std::min(bottom, v[axis]);
  return needle.vertices.empty() ? 0.0 : top - bottom;
}

// The block must hold the array's footprint (the bases of the outer needles).
void check_footprint(const IndentationCase& c) {
  const Eigen::Vector2d footprint = array_footprint(*c.array, base_diameter(c));
  for (const auto& [key, size, needed] : {std::tuple{"tissue.width", c.block.width, footprint.x()},
                                         std::tuple{"tissue.length", c.block.length, footprint.y()}}) {
    if (size < needed) {
      throw InvalidInput(fmt::format("{}: {} is too small for the array, whose footprint is {} across, expected at "
                                     "least {} or no {} (then the footprint plus array.margin on every side)",
                                     key, um(size), um(needed), um(needed), key));
    }
  }
}

}  // namespace

void set_array(IndentationCase& c, const NeedleArray& array, double tip_height, bool size_width, bool size_length) {
  c.array = array;
  const Eigen::Vector2d footprint = array_footprint(array, base_diameter(c));
  if (size_width) c.block.width = footprint.x() + 2 * array.margin;
  if (size_length) c.block.length = footprint.y() + 2 * array.margin;
  c.needles.clear();
  for (const Eigen::Vector2d& position : array_positions(array)) c.needles.push_back({position, tip_height});
}

double base_diameter(const IndentationCase& c) {
  if (c.geometry) return c.geometry->base_diameter;
  return std::max(extent(c.needle, 0), extent(c.needle, 1));
}

double needle_length(const IndentationCase& c) { return c.geometry ? c.geometry->length : extent(c.needle, 2); }

// Through a necessary condition: the area centroid of the needle's surface, turned by the azimuth, lies in the plane
// (within kMirrorCentroidTolerance of the base diameter). A cone's or a cylinder's does; a bevel's lies off its axis
// on the side away from its face.
double off_mirror_plane(const IndentationCase& c, int axis) {
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  double area = 0;
  for (const auto& t : c.needle.triangles) {
    const Eigen::Vector3d& p = c.needle.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& q = c.needle.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& r = c.needle.vertices[static_cast<std::size_t>(t[2])];
    const double triangle_area = 0.5 * (q - p).cross(r - p).norm();
    moment += triangle_area * ((p + q + r) / 3).head<2>();
    area += triangle_area;
  }
  if (!(area > 0)) return 0;
  const double offset = std::abs((Eigen::Rotation2Dd(c.azimuth) * (moment / area))[axis]);
  return offset <= kMirrorCentroidTolerance * base_diameter(c) ? 0.0 : offset;
}

IndentationCase modelled_case(const IndentationCase& c) {
  detail::ArrayModel model = detail::array_model(c);
  return model.reduced ? std::move(*model.reduced) : c;
}

namespace detail {

void validate_array_case(const IndentationCase& c) {
  if (!c.array) return;
  const NeedleArray& a = *c.array;
  validate(a, base_diameter(c));
  const std::vector<Eigen::Vector2d> positions = array_positions(a);
  bool matches = positions.size() == c.needles.size();
  for (std::size_t k = 0; matches && k < positions.size(); ++k) {
    matches = (positions[k] - c.needles[k].position).norm() <= 1e-9 * a.pitch &&
              c.needles[k].tip_height == c.needles.front().tip_height;
  }
  if (!matches) {
    throw InvalidInput(fmt::format("needles: {} needles, not the {} x {} array's, expected one needle per array "
                                   "position (array_positions) at the same tip height, or no [[needles]]",
                                   c.needles.size(), a.rows, a.columns));
  }
  if (!c.tissue_mesh) check_footprint(c);
  if (a.symmetry != ArraySymmetry::None && c.tissue_mesh) {
    throw InvalidInput("array.symmetry: a reduced model needs the block meshed here, not a tissue mesh file, expected "
                       "symmetry = \"none\" or a [tissue] block");
  }
  if (a.symmetry != ArraySymmetry::None && c.solver.boundary != fem::BoundaryCondition::SidesAndBottomFixed) {
    throw InvalidInput(fmt::format("array.symmetry: the reduced model keeps the sides and the bottom fixed, but "
                                   "[model] boundary = \"{}\", expected boundary = \"sides-and-bottom-fixed\" or "
                                   "symmetry = \"none\"",
                                   name_of(fem::kBoundaryConditionNames, c.solver.boundary)));
  }
  if (a.backing_plate && !(c.depth < needle_length(c))) {
    throw InvalidInput(fmt::format("loading.depth: {} reaches the needles' length {}: the backing plate would touch "
                                   "the tissue, which the model leaves out, expected a depth below the length",
                                   um(c.depth), um(needle_length(c))));
  }
}

ArrayModel array_model(const IndentationCase& c) {
  ArrayModel model;
  const int n = static_cast<int>(c.needles.size());
  if (!c.array || c.array->symmetry == ArraySymmetry::None) {
    model.source.resize(static_cast<std::size_t>(n));
    std::iota(model.source.begin(), model.source.end(), 0);
    model.multiplicity.assign(static_cast<std::size_t>(n), 1.0);
    return model;
  }
  // The needles are in array order (validate): needle k = row * columns + column. The half keeps the rows with
  // y >= 0, the quarter also the columns with x >= 0; a needle's mirror image across y = 0 is in row rows - 1 - row
  // (of the same x: the rows of a hexagonal half have the same shift), across x = 0 in column columns - 1 - column.
  const NeedleArray& a = *c.array;
  const bool quarter = a.symmetry == ArraySymmetry::Quarter;
  const auto kept_row = [&](int row) { return std::max(row, a.rows - 1 - row); };
  const auto kept_column = [&](int column) { return quarter ? std::max(column, a.columns - 1 - column) : column; };
  IndentationCase reduced = c;
  reduced.array.reset();
  reduced.needles.clear();
  if (quarter) reduced.block.width /= 2;
  reduced.block.length /= 2;
  reduced.solver.boundary = quarter ? fem::BoundaryCondition::QuarterSymmetry : fem::BoundaryCondition::HalfSymmetry;
  // The kept part of the block, x in [0, W/2] (quarter) and y in [0, L/2], re-centred on the origin (the block
  // mesher's frame): the symmetry planes become the faces x = min and y = min.
  const Eigen::Vector2d shift(quarter ? -c.block.width / 4 : 0.0, -c.block.length / 4);
  std::vector<int> solved(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < n; ++k) {
    const int row = k / a.columns, column = k % a.columns;
    if (kept_row(row) != row || kept_column(column) != column) continue;
    solved[static_cast<std::size_t>(k)] = static_cast<int>(reduced.needles.size());
    NeedleSite site = c.needles[static_cast<std::size_t>(k)];
    site.position += shift;
    reduced.needles.push_back(site);
  }
  for (int k = 0; k < n; ++k) {
    const int row = k / a.columns, column = k % a.columns;
    model.source.push_back(solved[static_cast<std::size_t>(kept_row(row) * a.columns + kept_column(column))]);
    const bool on_plane_y0 = 2 * row == a.rows - 1;                   // the middle row of an odd count
    const bool on_plane_x0 = quarter && 2 * column == a.columns - 1;  // the middle column of an odd count
    model.multiplicity.push_back((on_plane_y0 ? 2.0 : 1.0) * (on_plane_x0 ? 2.0 : 1.0));
  }
  model.factor = quarter ? 4.0 : 2.0;
  model.reduced = std::move(reduced);
  return model;
}

IndentationStep whole_step(const IndentationStep& solved, const ArrayModel& model) {
  IndentationStep step = solved;
  step.force *= model.factor;
  step.contact_area *= model.factor;
  step.strain_energy *= model.factor;
  step.external_work *= model.factor;
  if (model.reduced) {
    // With the mirror images of the solved part: the force's components normal to a symmetry plane (y; x too for a
    // quarter) cancel, and so do the moment's components in it (a moment is a pseudo-vector).
    const bool quarter = model.factor == 4.0;
    step.lateral_force = model.factor * Eigen::Vector3d(quarter ? 0.0 : solved.lateral_force.x(), 0.0,
                                                        solved.lateral_force.z());
    step.moment = model.factor * Eigen::Vector3d(0.0, quarter ? 0.0 : solved.moment.y(), 0.0);
  }
  step.needle_force.assign(model.source.size(), 0.0);
  step.needle_contact_area.assign(model.source.size(), 0.0);
  if (!solved.needle_averaged_pressure.empty()) step.needle_averaged_pressure.assign(model.source.size(), 0.0);
  for (std::size_t k = 0; k < model.source.size(); ++k) {
    const auto s = static_cast<std::size_t>(model.source[k]);
    step.needle_force[k] = model.multiplicity[k] * solved.needle_force[s];
    step.needle_contact_area[k] = model.multiplicity[k] * solved.needle_contact_area[s];
    // A pressure, not a resultant: a needle cut by a symmetry plane has the pressure of its solved part.
    if (!solved.needle_averaged_pressure.empty()) step.needle_averaged_pressure[k] = solved.needle_averaged_pressure[s];
  }
  return step;
}

}  // namespace detail
}  // namespace needlekit::insertion
