// The Gmsh part of mesh/surface_refill.hpp: the surface as one discrete Gmsh surface (its triangles given, never
// reparametrised, so Gmsh keeps them), the volume its surface loop bounds, and Delaunay 3D inside with the
// caller's sizes through a size callback.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "block_meshing_steps.hpp"
#include "gmsh_functions.hpp"
#include "gmsh_session.hpp"

namespace needlekit::mesh::detail {
namespace {

constexpr int kGmshTriangle = 2;

}  // namespace

TetMesh gmsh_refill(const SurfaceToFill& surface) {
  const double u = 1 / kModelUnit;  // m -> model units
  std::vector<std::size_t> node_tags(surface.nodes.size());
  std::vector<double> coords;
  coords.reserve(3 * surface.nodes.size());
  for (std::size_t k = 0; k < surface.nodes.size(); ++k) {
    node_tags[k] = k + 1;
    for (int i = 0; i < 3; ++i) coords.push_back(surface.nodes[k][i] * u);
  }
  std::vector<std::size_t> triangle_nodes;
  triangle_nodes.reserve(3 * surface.triangles.size());
  for (const std::array<int, 3>& t : surface.triangles)
    for (int a : t) triangle_nodes.push_back(static_cast<std::size_t>(a) + 1);

  TetMesh mesh;
  GmshSession session;
  try {
    gmsh::model::add("needlekit_refill");
    const int boundary = gmsh::model::addDiscreteEntity(2);
    gmsh::model::mesh::addNodes(2, boundary, node_tags, coords);
    gmsh::model::mesh::addElementsByType(boundary, kGmshTriangle, {}, triangle_nodes);
    const int volume = gmsh::model::geo::addVolume({gmsh::model::geo::addSurfaceLoop({boundary})});
    gmsh::model::geo::synchronize();
    gmsh::model::mesh::setSizeCallback([&](int, int, double x, double y, double z) {
      return surface.size(Eigen::Vector3d(x, y, z) / u) * u;
    });
    set_mesh_options(1);
    gmsh::model::mesh::generate(3);
    mesh = gmsh_tet_mesh({}, {{volume, 0}});
  } catch (...) {
    throw std::runtime_error(fmt::format("refilling the deformed tissue: Gmsh failed: {}", gmsh_error_message()));
  }
  // gmsh_tet_mesh numbers the nodes by tag: the surface's (tags 1..n) come first, in order, if every one is used.
  if (mesh.nodes.size() < surface.nodes.size())
    throw std::runtime_error("refilling the deformed tissue: Gmsh left surface nodes out of the tetrahedra");
  return mesh;
}

}  // namespace needlekit::mesh::detail
