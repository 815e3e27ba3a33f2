// The validation of an indentation case (insertion/indentation.hpp: validate, tissue_height): every key's range and
// the combinations that do not apply, as InvalidInput naming the case file's key.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <utility>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/needle/rounded_edges.hpp"
#include "array_model.hpp"

namespace needlekit::insertion {
namespace {

std::string um(double metres) { return fmt::format("{:.4g} um", metres * 1e6); }

// loading.angle and loading.azimuth: finite, 0 <= angle < 90 deg, and a tilt only with true contact and without
// a reduced array model (its symmetry planes assume vertical needles).
void validate_angle(const IndentationCase& c) {
  const double degrees = c.angle * 180 / M_PI;
  if (!std::isfinite(c.angle) || !(c.angle >= 0 && c.angle < M_PI / 2)) {
    throw InvalidInput(fmt::format("loading.angle: {:.6g} deg is outside [0, 90) deg, expected the needle's axis "
                                   "from the skin's normal, 0 <= angle < 90 deg",
                                   degrees));
  }
  if (!std::isfinite(c.azimuth)) {
    throw InvalidInput("loading.azimuth: not finite, expected an angle in the block's x-y plane from +x");
  }
  if (c.angle == 0) return;
  if (c.solver.contact != fem::ContactModel::Surface) {
    throw InvalidInput(fmt::format("loading.angle: {:.6g} deg with contact = \"tip-nodes\", whose nodes follow a flat "
                                   "tip straight down; expected angle = \"0 deg\" or model.contact = \"surface\"",
                                   degrees));
  }
  if (c.array && c.array->symmetry != ArraySymmetry::None) {
    throw InvalidInput(fmt::format("loading.angle: {:.6g} deg with array.symmetry = \"{}\", whose symmetry planes "
                                   "need vertical needles; expected angle = \"0 deg\" or no array.symmetry",
                                   degrees, name_of(kArraySymmetryNames, c.array->symmetry)));
  }
}

}  // namespace

double tissue_height(const IndentationCase& c) {
  if (c.tissue_mesh) {
    double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : c.tissue_mesh->nodes) top = std::max(top, p.z()), bottom = std::min(bottom, p.z());
    return c.tissue_mesh->nodes.empty() ? 0.0 : top - bottom;
  }
  double height = 0;
  for (const mesh::TissueLayer& layer : c.block.layers) height += layer.thickness;
  return height;
}

void validate(const IndentationCase& c) {
  if (c.needle.triangles.empty() || c.needle.vertices.empty()) {
    throw InvalidInput("needle: the needle surface mesh is empty, expected a closed triangle mesh");
  }
  if (c.edge_radius) {
    if (!c.geometry) {
      throw InvalidInput("needle.edge_radius: given for a needle given as a mesh, whose edges are the mesh's; "
                         "expected edge_radius only with a parametric needle (shape, tip_diameter, ...)");
    }
    if (c.solver.contact != fem::ContactModel::Surface) {
      throw InvalidInput("needle.edge_radius: given with contact = \"tip-nodes\", which takes the tip face as flat; "
                         "expected contact = \"surface\" or no edge_radius");
    }
  }
  if (c.geometry && c.solver.contact == fem::ContactModel::Surface) {
    needle::eroded_needle(*c.geometry, effective_edge_radius(c));  // throws for a radius outside its range
  }
  if (c.needles.empty()) throw InvalidInput("needles: no needle, expected at least one insertion site");
  detail::validate_array_case(c);
  for (std::size_t i = 0; i < c.needles.size(); ++i) {
    const NeedleSite& site = c.needles[i];
    if (!site.position.allFinite()) {
      throw InvalidInput(fmt::format("needles[{}]: the position is not finite, expected finite x and y", i));
    }
    if (!std::isfinite(site.tip_height) || site.tip_height < 0) {
      throw InvalidInput(fmt::format("needles[{}].tip_height: {} is below the surface: the needle would start inside "
                                     "the tissue, expected a tip height >= 0",
                                     i, um(site.tip_height)));
    }
    if (!c.tissue_mesh && !(std::abs(site.position.x()) < c.block.width / 2 &&
                            std::abs(site.position.y()) < c.block.length / 2)) {
      throw InvalidInput(fmt::format("needles[{}]: ({}, {}) is outside the {} x {} block, expected |x| < width/2 and "
                                     "|y| < length/2",
                                     i, um(site.position.x()), um(site.position.y()), um(c.block.width),
                                     um(c.block.length)));
    }
  }
  if (!std::isfinite(c.depth) || !(c.depth > 0)) {
    throw InvalidInput(fmt::format("loading.depth: {} is not positive, expected a depth > 0", um(c.depth)));
  }
  validate_angle(c);
  const double height = tissue_height(c);
  if (height > 0 && !(c.depth * std::cos(c.angle) < height)) {
    throw InvalidInput(fmt::format("loading.depth: {} reaches through the {} high tissue block, expected a depth below "
                                   "its height (tissue.height or the layers' thicknesses){}",
                                   um(c.depth), um(height), c.angle > 0 ? " over the cosine of loading.angle" : ""));
  }
  if (!c.tissue_mesh) {  // the mesh sizes under the case file's keys (the CLI's overrides land here too)
    for (const auto& [key, size] : {std::pair{"mesh.size_at_tip", c.block.size_at_site},
                                    std::pair{"mesh.size_far", c.block.size_far}}) {
      if (!std::isfinite(size) || !(size > 0)) {
        throw InvalidInput(fmt::format("{}: {} is not positive, expected a size > 0", key, um(size)));
      }
    }
    if (c.block.size_far < c.block.size_at_site) {
      throw InvalidInput(fmt::format("mesh.size_far: {} is smaller than mesh.size_at_tip = {}, expected size_far >= "
                                     "size_at_tip",
                                     um(c.block.size_far), um(c.block.size_at_site)));
    }
  }
  if (c.solver.linear_solver == fem::LinearSolver::TwoGrid && c.solver.order == fem::ElementOrder::Linear &&
      c.tissue_mesh) {
    throw InvalidInput(
        "solver.linear_solver: \"two-grid\" with linear elements needs a block meshed here (its coarse "
        "level is the block meshed at coarser sizes), not a tissue mesh file; expected another "
        "linear_solver, or quadratic elements");
  }
  if (c.steps < 1) throw InvalidInput(fmt::format("loading.steps: {} is not >= 1, expected at least one step", c.steps));
  c.solver.validate();
  validate(c.puncture);
  if (c.puncture.criterion == PunctureLaw::AveragedPressure && c.solver.contact != fem::ContactModel::Surface) {
    throw InvalidInput("puncture.criterion: \"averaged-pressure\" with contact = \"tip-nodes\", whose nodes follow a "
                       "flat tip face and give no contact field; expected model.contact = \"surface\" or criterion = "
                       "\"dissertation\"");
  }
}

}  // namespace needlekit::insertion
