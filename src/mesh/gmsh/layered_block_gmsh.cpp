// The layered block with the Gmsh C++ API: one OpenCASCADE box per layer, fragmented so that the layer interfaces
// are conforming; a physical volume named after each layer; the insertion sites (and optionally a circle around
// each) embedded in the top surface; size fields: Distance from the sites -> Threshold (size_at_site within
// refinement_radius, growing by size_gradient up to size_far), a Box field capping the size in each thin layer, and
// their Min as background mesh; Delaunay 3D on one thread (reproducible).
// The geometry is built in micrometres (OpenCASCADE's absolute tolerance is 1e-7 model units) and converted to m.
// Part of the Gmsh module; the options are validated by layered_block_mesh (src/mesh/layered_block_mesh.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "block_meshing_steps.hpp"
#include "gmsh_functions.hpp"
#include "gmsh_session.hpp"

namespace needlekit::mesh::detail {
namespace {

constexpr int kGmshTet4 = 4;  // Gmsh element type: 4-node tetrahedron

int add_field(const std::string& type) { return gmsh::model::mesh::field::add(type); }

// Sets the first of `names` that this Gmsh version knows on `field` (field option names changed between versions).
template <class Value>
void set_field_option(int field, const std::vector<std::string>& names, const Value& value) {
  for (const std::string& name : names) {
    try {
      if constexpr (std::is_arithmetic_v<Value>) {
        gmsh::model::mesh::field::setNumber(field, name, value);
      } else {
        gmsh::model::mesh::field::setNumbers(field, name, value);
      }
      return;
    } catch (...) {
    }
  }
  throw std::logic_error("Gmsh field option " + names.front() + " unknown");
}

}  // namespace

std::vector<int> fragmented_volumes(const std::vector<std::pair<int, int>>& boxes) {
  if (boxes.size() == 1) return {boxes[0].second};
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  gmsh::model::occ::fragment({boxes.front()}, gmsh::vectorpair(boxes.begin() + 1, boxes.end()), out, map);
  std::vector<int> volumes;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (map.at(i).size() != 1 || map[i][0].first != 3) {
      throw std::logic_error(fmt::format("fragment split box {} into {} entities", i, map.at(i).size()));
    }
    volumes.push_back(map[i][0].second);
  }
  return volumes;
}

TetMesh gmsh_tet_mesh(const std::vector<TissueLayer>& layers, const std::vector<VolumeLayer>& volumes) {
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  std::size_t max_tag = 0;
  for (std::size_t tag : node_tags) max_tag = std::max(max_tag, tag);
  std::vector<int> index_of_tag(max_tag + 1, -1);
  TetMesh mesh;
  mesh.layers = layers;
  std::vector<std::vector<std::size_t>> volume_nodes(volumes.size());
  for (std::size_t i = 0; i < volumes.size(); ++i) {
    std::vector<std::size_t> element_tags;
    gmsh::model::mesh::getElementsByType(kGmshTet4, element_tags, volume_nodes[i], volumes[i].volume);
    for (std::size_t tag : volume_nodes[i]) index_of_tag.at(tag) = 0;  // mark used
  }
  std::vector<int> position_of_tag(max_tag + 1, -1);
  for (std::size_t k = 0; k < node_tags.size(); ++k) position_of_tag[node_tags[k]] = static_cast<int>(k);
  for (std::size_t tag = 0; tag <= max_tag; ++tag) {
    if (index_of_tag[tag] < 0) continue;
    const int k = position_of_tag[tag];
    if (k < 0) throw std::logic_error(fmt::format("node {} has no coordinates", tag));
    index_of_tag[tag] = static_cast<int>(mesh.nodes.size());
    mesh.nodes.emplace_back(Eigen::Vector3d(coords[3 * k], coords[3 * k + 1], coords[3 * k + 2]) * kModelUnit);
  }
  for (std::size_t i = 0; i < volumes.size(); ++i) {
    const auto& n = volume_nodes[i];
    for (std::size_t e = 0; e + 3 < n.size(); e += 4) {
      mesh.tets.push_back({index_of_tag[n[e]], index_of_tag[n[e + 1]], index_of_tag[n[e + 2]], index_of_tag[n[e + 3]]});
      mesh.tet_layer.push_back(volumes[i].layer);
    }
  }
  return mesh;
}

namespace {

// Sites on the top face's edges: points to embed in its boundary curves, and corners (the block's vertices).
struct EdgeSites {
  std::vector<int> points;                     // added OCC points, on an edge
  std::vector<Eigen::Vector2d> positions;      // model units, of `points`
  std::vector<Eigen::Vector2d> corners;        // model units
};

// Embeds each edge site in the boundary curve of the top face that holds it and appends its point, or the corner's
// vertex, to `site_points` (the refinement grows from them).
void embed_edge_sites(const EdgeSites& sites, const std::pair<int, int>& top, double eps, std::vector<int>& site_points) {
  gmsh::vectorpair curves;
  gmsh::model::getBoundary({top}, curves, false, false, false);
  for (std::size_t k = 0; k < sites.points.size(); ++k) {
    const Eigen::Vector2d& p = sites.positions[k];
    int holder = -1;
    for (const auto& curve : curves) {
      double x0, y0, z0, x1, y1, z1;
      gmsh::model::getBoundingBox(1, std::abs(curve.second), x0, y0, z0, x1, y1, z1);
      if (p.x() > x0 - eps && p.x() < x1 + eps && p.y() > y0 - eps && p.y() < y1 + eps) holder = std::abs(curve.second);
    }
    if (holder < 0) throw std::logic_error(fmt::format("no top edge holds the site at ({}, {})", p.x(), p.y()));
    gmsh::model::mesh::embed(0, {sites.points[k]}, 1, holder);
    site_points.push_back(sites.points[k]);
  }
  for (const Eigen::Vector2d& p : sites.corners) {
    gmsh::vectorpair vertex;
    gmsh::model::getEntitiesInBoundingBox(p.x() - eps, p.y() - eps, -eps, p.x() + eps, p.y() + eps, eps, vertex, 0);
    if (vertex.size() != 1) throw std::logic_error(fmt::format("{} block vertices at a corner site", vertex.size()));
    site_points.push_back(vertex[0].second);
  }
}

// The layers as stacked boxes (model units), fragmented so that neighbouring layers share their interface.
LayerVolumes layer_volumes(const std::vector<TissueLayer>& layers, double w, double l, double u) {
  LayerVolumes result;
  gmsh::vectorpair boxes;
  double z = 0;
  for (const TissueLayer& layer : layers) {
    result.tops.push_back(z);
    const double t = layer.thickness * u;
    boxes.emplace_back(3, gmsh::model::occ::addBox(-0.5 * w, -0.5 * l, z - t, w, l, t));
    z -= t;
  }
  result.height = -z;
  result.volume_of_layer = fragmented_volumes(boxes);
  return result;
}

// The insertion sites as points (and circles of site_circle_radius) on the top face z = 0, embedded there so that
// they become mesh nodes; returns the site points' tags (for the size field).
std::vector<int> embed_sites(const LayeredBlockOptions& options, double w, double l, double u, double eps) {
  EdgeSites edge_sites;
  std::vector<int> site_points, site_circles;
  for (const Eigen::Vector2d& s : options.insertion_sites) {
    const bool on_x = std::abs(s.x() * u) > 0.5 * w - 1e-9 * w, on_y = std::abs(s.y() * u) > 0.5 * l - 1e-9 * l;
    // On the top face's edge (a symmetry plane of a reduced model): exactly on it, a node of that edge.
    const double x = on_x ? std::copysign(0.5 * w, s.x()) : s.x() * u, y = on_y ? std::copysign(0.5 * l, s.y()) : s.y() * u;
    if (on_x && on_y) {  // a corner: the block's own vertex
      edge_sites.corners.emplace_back(x, y);
      continue;
    }
    (on_x || on_y ? edge_sites.points : site_points).push_back(gmsh::model::occ::addPoint(x, y, 0));
    if (on_x || on_y) edge_sites.positions.emplace_back(x, y);
    if (options.site_circle_radius > 0) {
      site_circles.push_back(gmsh::model::occ::addCircle(x, y, 0, options.site_circle_radius * u));
    }
  }
  gmsh::model::occ::synchronize();
  gmsh::vectorpair top;
  gmsh::model::getEntitiesInBoundingBox(-0.5 * w - eps, -0.5 * l - eps, -eps, 0.5 * w + eps, 0.5 * l + eps, eps, top, 2);
  if (top.size() != 1) throw std::logic_error(fmt::format("{} top surfaces", top.size()));
  if (!site_points.empty()) gmsh::model::mesh::embed(0, site_points, 2, top[0].second);
  if (!site_circles.empty()) gmsh::model::mesh::embed(1, site_circles, 2, top[0].second);
  embed_edge_sites(edge_sites, top[0], eps, site_points);
  return site_points;
}

}  // namespace

// The horizontal faces of a thin layer must not carry the same triangulation: with every node of the top face
// straight above one of the bottom face, the vertical rectangles between them are cocircular and the 3D mesher
// leaves flat slivers there (zero volume; seen in half of the runs of a 20 um stratum corneum meshed at 40 um,
// with HXT and with Delaunay). The interfaces and the bottom alternate between Delaunay (5) and the top's
// Frontal-Delaunay (6) triangulations, which place their nodes differently.
void alternate_interface_algorithms(const LayerVolumes& volumes, double w, double l, double eps) {
  const std::size_t n = volumes.tops.size();
  for (std::size_t i = 1; i <= n; ++i) {
    const double zi = i < n ? volumes.tops[i] : -volumes.height;
    gmsh::vectorpair faces;
    gmsh::model::getEntitiesInBoundingBox(-0.5 * w - eps, -0.5 * l - eps, zi - eps, 0.5 * w + eps, 0.5 * l + eps,
                                          zi + eps, faces, 2);
    for (const auto& face : faces) gmsh::model::mesh::setAlgorithm(2, face.second, i % 2 == 1 ? 5 : 6);
  }
}

// The background size field: size_at_site within refinement_radius of the sites, growing at size_gradient to
// size_far, and capped in each thin layer at thin_layer_size_factor times its thickness.
void set_size_fields(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                     const LayerVolumes& volumes, const std::vector<int>& site_points, double w, double l, double u) {
  const double size_site = options.size_at_site * u, size_far = options.size_far * u;
  const double radius = options.refinement_radius * u;
  std::vector<double> fields;
  if (!site_points.empty()) {
    const int distance = add_field("Distance");
    set_field_option(distance, {"PointsList", "NodesList"}, std::vector<double>(site_points.begin(), site_points.end()));
    const int threshold = add_field("Threshold");
    set_field_option(threshold, {"InField", "IField"}, distance);
    set_field_option(threshold, {"SizeMin", "LcMin"}, size_site);
    set_field_option(threshold, {"SizeMax", "LcMax"}, size_far);
    set_field_option(threshold, {"DistMin"}, radius);
    set_field_option(threshold, {"DistMax"}, radius + (size_far - size_site) / options.size_gradient);
    fields.push_back(threshold);
  }
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const double cap = options.thin_layer_size_factor * layers[i].thickness * u;
    if (cap <= 0 || cap >= size_far) continue;
    const int box = add_field("Box");
    set_field_option(box, {"VIn"}, cap);
    set_field_option(box, {"VOut"}, size_far);
    set_field_option(box, {"XMin"}, -w);
    set_field_option(box, {"XMax"}, w);
    set_field_option(box, {"YMin"}, -l);
    set_field_option(box, {"YMax"}, l);
    set_field_option(box, {"ZMin"}, volumes.tops[i] - layers[i].thickness * u - 1e-6 * volumes.height);
    set_field_option(box, {"ZMax"}, volumes.tops[i] + 1e-6 * volumes.height);
    set_field_option(box, {"Thickness"}, (size_far - cap) / options.size_gradient);
    fields.push_back(box);
  }
  if (!fields.empty()) {
    const int min = add_field("Min");
    set_field_option(min, {"FieldsList"}, fields);
    gmsh::model::mesh::field::setAsBackgroundMesh(min);
  }
  GmshSession::set_option({"Mesh.MeshSizeMax", "Mesh.CharacteristicLengthMax"}, size_far);
}

// The meshing algorithms and the threads.
void set_mesh_options(int threads_option) {
  GmshSession::set_option({"Mesh.MeshSizeFromPoints", "Mesh.CharacteristicLengthFromPoints"}, 0);
  GmshSession::set_option({"Mesh.MeshSizeFromCurvature", "Mesh.CharacteristicLengthFromCurvature"}, 0);
  GmshSession::set_option({"Mesh.MeshSizeExtendFromBoundary", "Mesh.CharacteristicLengthExtendFromBoundary"}, 0);
  GmshSession::set_option({"Mesh.Algorithm"}, 6);     // Frontal-Delaunay surfaces
  // Reproducible meshes: Gmsh 4.8's HXT (10) gives meshes that depend on the heap layout even on one thread (the
  // same case gave 11,158-11,308 tetrahedra depending on the case file's name or the environment's size), and
  // several threads make the 2D meshes differ in their last bits. Delaunay 3D (1) on one thread gives the same
  // mesh, bit for bit, whatever the memory layout (tests/example/test_mesh_determinism.cpp), at about HXT's speed on
  // these blocks (and about 20 % more elements for the same size field).
  GmshSession::set_option({"Mesh.Algorithm3D"}, 1);
  const int threads = threads_option == 0 ? 1 : threads_option;
  GmshSession::set_option({"General.NumThreads"}, threads);
  GmshSession::set_option({"Mesh.MaxNumThreads2D"}, threads);
  GmshSession::set_option({"Mesh.MaxNumThreads3D"}, threads);
  GmshSession::set_option({"Mesh.Optimize"}, 1);
}

// The Gmsh part: geometry, size fields, Delaunay 3D, conversion to a TetMesh (no orientation, quality or timing).
TetMesh gmsh_layered_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers) {
  const double u = 1 / kModelUnit;  // m -> model units
  const double w = options.width * u, l = options.length * u;
  TetMesh mesh;
  GmshSession session;
  try {
    gmsh::model::add("needlekit_layered_block");
    const LayerVolumes volumes = layer_volumes(layers, w, l, u);
    const double eps = 1e-3 * std::min({w, l, layers.front().thickness * u});
    const std::vector<int> site_points = embed_sites(options, w, l, u, eps);
    alternate_interface_algorithms(volumes, w, l, eps);
    for (std::size_t i = 0; i < layers.size(); ++i) {
      const int group = gmsh::model::addPhysicalGroup(3, {volumes.volume_of_layer[i]});
      gmsh::model::setPhysicalName(3, group, layers[i].name);
    }
    set_size_fields(options, layers, volumes, site_points, w, l, u);
    set_mesh_options(options.threads);
    gmsh::model::mesh::generate(3);
    std::vector<VolumeLayer> volume_layers;
    for (std::size_t i = 0; i < layers.size(); ++i) volume_layers.push_back({volumes.volume_of_layer[i], static_cast<int>(i)});
    mesh = gmsh_tet_mesh(layers, volume_layers);
  } catch (...) {
    throw std::runtime_error(fmt::format("layered block: Gmsh failed: {}", gmsh_error_message()));
  }
  return mesh;
}

}  // namespace needlekit::mesh::detail
