// A parametric layered tissue block: the options checked here, the mesh made by the Gmsh module
// (src/mesh/gmsh/layered_block_gmsh.cpp, opened on first use) or, for a square needle array, assembled from copies of
// its cell (src/mesh/gmsh/cell_block_gmsh.cpp, mirrored_cell.hpp, cell_replication.hpp), then optionally split,
// reoriented and rated here.
#include "needlekit/mesh/layered_block_mesh.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "gmsh_module.hpp"
#include "mirrored_cell.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/cell_replication.hpp"
#include "needlekit/mesh/mesh_validation.hpp"
#include "needlekit/mesh/tet_count_estimate.hpp"
#include "needlekit/mesh/uniform_refinement.hpp"

namespace needlekit::mesh {
namespace {

constexpr double kMinRelativeDimension = 1e-5;  // of the block's largest dimension, for every dimension and layer

void check_positive(double value, std::string_view field, double scale = 1e6, std::string_view unit = "um") {
  if (!std::isfinite(value) || value <= 0) {
    throw InvalidInput(fmt::format("layered block: {} = {} {}; expected a positive value", field, value * scale, unit));
  }
}

void validate_options(const LayeredBlockOptions& o, const std::vector<TissueLayer>& layers) {
  check_positive(o.width, "width");
  check_positive(o.length, "length");
  check_positive(o.size_at_site, "size_at_site");
  check_positive(o.refinement_radius, "refinement_radius");
  check_positive(o.size_far, "size_far");
  check_positive(o.size_gradient, "size_gradient", 1, "");
  if (o.size_far < o.size_at_site) {
    throw InvalidInput(fmt::format("layered block: size_far = {:g} um is smaller than size_at_site = {:g} um; expected "
                                   "size_far >= size_at_site",
                                   o.size_far * 1e6, o.size_at_site * 1e6));
  }
  if (!std::isfinite(o.coarse_size_factor) || o.coarse_size_factor <= 1) {
    throw InvalidInput(fmt::format("layered block: coarse_size_factor = {}; expected a value > 1", o.coarse_size_factor));
  }
  if (!std::isfinite(o.thin_layer_size_factor) || o.thin_layer_size_factor < 0) {
    throw InvalidInput(fmt::format("layered block: thin_layer_size_factor = {}; expected a value >= 0 (0 = no cap)",
                                   o.thin_layer_size_factor));
  }
  if (!std::isfinite(o.site_circle_radius) || o.site_circle_radius < 0) {
    throw InvalidInput(fmt::format("layered block: site_circle_radius = {:g} um; expected >= 0 (0 = none)",
                                   o.site_circle_radius * 1e6));
  }
  if (o.site_circle_radius > 0) {
    for (std::size_t s = 0; s < o.insertion_sites.size(); ++s) {
      const Eigen::Vector2d& p = o.insertion_sites[s];
      const double r = o.site_circle_radius;
      if (!(std::abs(p.x()) + r < 0.5 * o.width && std::abs(p.y()) + r < 0.5 * o.length)) {
        throw InvalidInput(fmt::format("layered block: the {:g} um circle of site {} at ({:g}, {:g}) um leaves the top "
                                       "surface; expected it inside",
                                       r * 1e6, s, p.x() * 1e6, p.y() * 1e6));
      }
      for (std::size_t t = 0; t < s; ++t) {
        if ((o.insertion_sites[t] - p).norm() <= 2 * r) {
          throw InvalidInput(fmt::format("layered block: the {:g} um circles of sites {} and {} overlap; expected "
                                         "sites more than {:g} um apart",
                                         r * 1e6, t, s, 2 * r * 1e6));
        }
      }
    }
  }
  materials::validate(layers, "layered block: layers");
  // OpenCASCADE models the block in um with an absolute tolerance of 1e-7 um and fails (or finds no top face) for a
  // layer that is thin next to the block: every dimension must be at least kMinRelativeDimension of the largest.
  double height = 0;
  for (const TissueLayer& layer : layers) height += layer.thickness;
  const double largest = std::max({o.width, o.length, height});
  const auto check_dimension = [&](double value, const std::string& what) {
    if (!(value >= kMinRelativeDimension * largest)) {
      throw InvalidInput(fmt::format("layered block: {} = {:g} um is below {:g} of the block's largest dimension "
                                     "({:g} um); expected a thicker layer or a smaller block",
                                     what, value * 1e6, kMinRelativeDimension, largest * 1e6));
    }
  };
  check_dimension(o.width, "width");
  check_dimension(o.length, "length");
  for (const TissueLayer& layer : layers) check_dimension(layer.thickness, fmt::format("layer '{}' thickness", layer.name));
  if (!(o.max_tetrahedra > 0)) {
    throw InvalidInput(fmt::format("layered block: max_tetrahedra = {}; expected a positive count", o.max_tetrahedra));
  }
  if (o.threads < 0) throw InvalidInput(fmt::format("layered block: threads = {}; expected >= 0", o.threads));
  for (std::size_t s = 0; s < o.insertion_sites.size(); ++s) {
    const Eigen::Vector2d& p = o.insertion_sites[s];
    // On the edge is allowed: a needle on a symmetry plane of a reduced model (the edge gets a node there).
    if (!(std::abs(p.x()) <= 0.5 * o.width && std::abs(p.y()) <= 0.5 * o.length)) {
      throw InvalidInput(fmt::format("layered block: insertion site {} at ({:g}, {:g}) um is not on the top surface "
                                     "(|x| <= {:g} um, |y| <= {:g} um)",
                                     s, p.x() * 1e6, p.y() * 1e6, 0.5 * o.width * 1e6, 0.5 * o.length * 1e6));
    }
  }
}

// The block meshed by the Gmsh module, right-handed.
TetMesh gmsh_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers) {
  detail::GmshError error;
  TetMesh mesh;
  {
    const std::lock_guard<std::mutex> lock(detail::gmsh_call_mutex());
    mesh = detail::gmsh_module().layered_block(options, layers, error);
  }
  detail::throw_if_failed(error);
  reoriented_count(mesh);
  return mesh;
}

// The block assembled from copies of the array cell meshed by the Gmsh module (cell_replication.hpp), right-handed.
TetMesh replicated_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                         const SiteGrid& grid) {
  detail::GmshError error;
  detail::CellBlockMesh cell;
  detail::CellLayout layout{grid.pitch_x,      grid.pitch_y,       grid.sites,
                            grid.top_row_sites, grid.sites_on_corners, grid.margin_left,
                            grid.margin_right,  grid.margin_bottom, grid.margin_top};
  layout.quadrant = detail::mirrors_from_a_quadrant(layout, options);
  {
    const std::lock_guard<std::mutex> lock(detail::gmsh_call_mutex());
    cell = detail::gmsh_module().cell_block(options, layers, layout, error);
  }
  detail::throw_if_failed(error);
  if (layout.quadrant) cell = detail::mirrored_cell(cell, layout);
  reoriented_count(cell.mesh);  // before the copies: a translation keeps the orientation
  return replicated_cells(cell.mesh, cell.piece, grid);
}

// The block by the cells when `grid` is given, else whole.
TetMesh meshed_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                     const std::optional<SiteGrid>& grid) {
  return grid ? replicated_block(options, layers, *grid) : gmsh_block(options, layers);
}

// The block, whole or (with a grid) from the cells: checked, estimated, meshed, split or with its coarse level.
LayeredBlockResult block_mesh(const LayeredBlockOptions& options, const std::optional<SiteGrid>& grid) {
  const std::vector<TissueLayer> layers = options.layers.empty() ? materials::skin_layers() : options.layers;
  validate_options(options, layers);
  LayeredBlockOptions estimated = options;
  estimated.layers = layers;
  if (const double tets = estimated_tetrahedra(estimated); !(tets <= options.max_tetrahedra)) {
    throw InvalidInput(fmt::format("layered block: about {:.2g} tetrahedra (estimated from the block and mesh sizes), "
                                   "more than the limit of {:.2g}; expected coarser sizes ([mesh] size_at_tip, "
                                   "size_far, size_gradient) or a smaller block, or raise [mesh] max_tetrahedra",
                                   tets, options.max_tetrahedra));
  }
  const auto start = std::chrono::steady_clock::now();
  LayeredBlockResult result;
  // The split's parent at twice the sizes, or the coarse level's own mesh at coarse_size_factor times them.
  LayeredBlockOptions coarse = options;
  const double factor = options.split ? 2.0 : options.coarse_size_factor;
  coarse.size_at_site *= factor;
  coarse.size_far *= factor;
  coarse.size_gradient *= factor;  // the same grading distances
  coarse.thin_layer_size_factor *= factor;
  if (options.split) {
    UniformRefinement refined = refine_uniformly(meshed_block(coarse, layers, grid));
    result.mesh = std::move(refined.mesh);
    result.coarse = std::move(refined.coarse);
  } else {
    result.mesh = meshed_block(options, layers, grid);
    if (options.coarse_level) {
      result.coarse = interpolating_coarse_level(result.mesh, meshed_block(coarse, layers, grid));
    }
  }
  result.quality = layer_quality(result.mesh);
  result.mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

LayeredBlockResult layered_block_mesh(const LayeredBlockOptions& options) { return block_mesh(options, std::nullopt); }

ArrayBlockMesh array_block_mesh(const LayeredBlockOptions& options, const CellLattice& lattice) {
  SiteGridCheck check = site_grid(options, lattice);
  ArrayBlockMesh result;
  result.block = block_mesh(options, check.grid);
  result.meshing = check.grid ? BlockMeshing::ReplicatedCell : BlockMeshing::WholeBlock;
  result.reason = std::move(check.reason);
  return result;
}

}  // namespace needlekit::mesh
