#include "needlekit/patch/patch_design.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/patch/patch_design_parameters.hpp"

namespace needlekit::patch {

std::string_view to_string(SpringDirection direction) { return name_of(kSpringDirectionNames, direction); }

PatchDesign patch_design(const PatchDesignOptions& o) {
  check_ranges(kPatchDesignParameters, o, "patch design");
  needle::validate(o.needle, "needle");
  materials::validate(o.material, "needle.material");

  PatchDesign d;
  d.nodes_u = o.needles_u;
  d.nodes_v = o.needles_v;
  d.width_u = o.width_u;
  d.width_v = o.width_v;
  d.pitch_u = o.width_u / o.needles_u;  // Eq 4.25: Pxy = w/n
  d.pitch_v = o.width_v / o.needles_v;
  d.needle = o.needle;
  d.material = o.material;
  d.rest_positions.resize(d.node_count());
  d.inner.resize(d.node_count());
  for (int j = 0; j < d.nodes_v; ++j) {
    for (int i = 0; i < d.nodes_u; ++i) {
      d.rest_positions[d.node(i, j)] = {(i - 0.5 * (d.nodes_u - 1)) * d.pitch_u, (j - 0.5 * (d.nodes_v - 1)) * d.pitch_v};
      d.inner[d.node(i, j)] = i > 0 && j > 0 && i < d.nodes_u - 1 && j < d.nodes_v - 1;
    }
  }
  // Fig 5.6: structural springs along U and V, shear springs along both diagonals.
  const double diagonal = std::hypot(d.pitch_u, d.pitch_v);
  for (int j = 0; j < d.nodes_v; ++j) {
    for (int i = 0; i < d.nodes_u; ++i) {
      if (i + 1 < d.nodes_u) d.springs.push_back({d.node(i, j), d.node(i + 1, j), SpringDirection::U, d.pitch_u, o.stiffness_u});
      if (j + 1 < d.nodes_v) d.springs.push_back({d.node(i, j), d.node(i, j + 1), SpringDirection::V, d.pitch_v, o.stiffness_v});
      if (i + 1 < d.nodes_u && j + 1 < d.nodes_v) {
        d.springs.push_back({d.node(i, j), d.node(i + 1, j + 1), SpringDirection::Diagonal, diagonal, o.stiffness_diagonal});
        d.springs.push_back({d.node(i + 1, j), d.node(i, j + 1), SpringDirection::AntiDiagonal, diagonal, o.stiffness_diagonal});
      }
    }
  }
  return d;
}

std::vector<int> neighbors(const PatchDesign& design, int node) {
  static constexpr int kSteps[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  const int i = design.column(node), j = design.row(node);
  std::vector<int> result;
  result.reserve(8);
  for (const auto& step : kSteps) {
    const int a = i + step[0], b = j + step[1];
    if (a >= 0 && b >= 0 && a < design.nodes_u && b < design.nodes_v) result.push_back(design.node(a, b));
  }
  return result;
}

}  // namespace needlekit::patch
