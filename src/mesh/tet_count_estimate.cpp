#include "needlekit/mesh/tet_count_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "needlekit/materials/tissue_presets.hpp"

namespace needlekit::mesh {
namespace {

double density(double size) { return kTetsPerCubicSize / (size * size * size); }

// Volume of the part of a ball of radius r about a point of the top surface that lies in a slab of depth h under
// it: a half ball, or for r > h the half ball cut at depth h (pi (r^2 h - h^3 / 3)).
double half_ball_in_slab(double r, double h) {
  const double pi = std::numbers::pi;
  return r <= h ? 2.0 / 3.0 * pi * r * r * r : pi * (r * r * h - h * h * h / 3);
}

}  // namespace

double estimated_tetrahedra(const LayeredBlockOptions& o) {
  const std::vector<TissueLayer> layers = o.layers.empty() ? materials::skin_layers() : o.layers;
  double height = 0;
  for (const TissueLayer& layer : layers) height += layer.thickness;
  const double area = o.width * o.length;
  const double volume = area * height;
  const double far = o.size_far;
  double count = volume * density(far);

  // The refinement around each site: size_at_site within refinement_radius, then h(d) = size_at_site +
  // size_gradient (d - refinement_radius) up to size_far (layered_block_mesh's Threshold field). Each extra term is
  // the density above the far field's, over the part of the half ball inside the block's depth, capped by the
  // block's volume.
  const double reach = std::sqrt(o.width * o.width + o.length * o.length + height * height);
  const double graded_end = o.refinement_radius + (far - o.size_at_site) / o.size_gradient;
  for (std::size_t s = 0; s < o.insertion_sites.size(); ++s) {
    const double r = std::min(o.refinement_radius, reach);
    double inner = std::min(half_ball_in_slab(r, height), volume);
    count += inner * (density(o.size_at_site) - density(far));
    const double end = std::min(graded_end, reach);
    if (end <= r) continue;
    // Simpson's rule over the graded shell, shell volume dV = d(half_ball_in_slab) / dd.
    constexpr int kIntervals = 512;
    const double step = (end - r) / kIntervals;
    double shell = 0, shell_volume = 0;
    for (int i = 0; i <= kIntervals; ++i) {
      const double d = r + i * step;
      const double size = std::min(far, o.size_at_site + o.size_gradient * (d - o.refinement_radius));
      const double surface = 2 * std::numbers::pi * d * std::min(d, height);
      const double weight = (i == 0 || i == kIntervals) ? 1 : (i % 2 ? 4 : 2);
      shell += weight * surface * (density(size) - density(far));
      shell_volume += weight * surface;
    }
    shell *= step / 3;
    shell_volume *= step / 3;
    // Past the block's volume the shell lies outside it: scale down to the block.
    if (inner + shell_volume > volume) shell *= std::max(0.0, volume - inner) / shell_volume;
    count += shell;
  }

  // The cap in each thin layer (cap = thin_layer_size_factor * thickness below size_far), and its transition to
  // size_far over (size_far - cap) / size_gradient on one side: integral of density(cap + g s) ds =
  // kTetsPerCubicSize / (2 g) (1 / cap^2 - 1 / (cap + g T)^2).
  for (const TissueLayer& layer : layers) {
    const double cap = o.thin_layer_size_factor * layer.thickness;
    if (cap <= 0 || cap >= far) continue;
    count += area * layer.thickness * (density(cap) - density(far));
    const double g = o.size_gradient;
    const double transition = std::min((far - cap) / g, height);
    const double end_size = cap + g * transition;
    count += area * (kTetsPerCubicSize / (2 * g) * (1 / (cap * cap) - 1 / (end_size * end_size)) -
                     transition * density(far));
  }
  return count;
}

}  // namespace needlekit::mesh
