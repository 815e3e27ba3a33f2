#include "function_space.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "needlekit/core/errors.hpp"
#include "needlekit/fem/tet_element.hpp"
#include "tet_kernel.hpp"

namespace needlekit::fem::detail {
namespace {

template <class T>
std::string str(T v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void check(bool ok, const std::string& message) {
  if (!ok) throw InvalidInput(message);
}

}  // namespace

namespace {

// Per tetrahedron its own reference edges (mesh::OwnReference), or null: it is shaped by its nodes.
std::vector<const Eigen::Matrix3d*> own_edges(const mesh::TetMesh& mesh) {
  std::vector<const Eigen::Matrix3d*> own(mesh.tets.size(), nullptr);
  for (const mesh::OwnReference& r : mesh.own_reference) {
    check(r.tet >= 0 && r.tet < static_cast<int>(mesh.tets.size()),
          "tissue mesh: an own reference names tetrahedron " + str(r.tet) + " of " + str(mesh.tets.size()));
    own[static_cast<size_t>(r.tet)] = &r.edges;
  }
  return own;
}

// Corner i of a tetrahedron's reference shape: its node `node`'s position, or with its own edges, 0 and the edges.
Eigen::Vector3d reference_corner(const Eigen::Matrix3d* own, int i, const Eigen::Vector3d& node) {
  if (!own) return node;
  return i == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(own->col(i - 1));
}

}  // namespace

void validate_tissue_mesh(const mesh::TetMesh& mesh) {
  check(!mesh.nodes.empty() && !mesh.tets.empty(), "tissue mesh: no nodes or no tetrahedra");
  check(mesh.tet_layer.size() == mesh.tets.size(), "tissue mesh: tet_layer has " + str(mesh.tet_layer.size()) +
        " entries for " + str(mesh.tets.size()) + " tetrahedra");
  for (size_t l = 0; l < mesh.layers.size(); ++l) {
    const auto& L = mesh.layers[l];
    check(L.youngs_modulus > 0 && std::isfinite(L.youngs_modulus),
          "tissue layer \"" + L.name + "\": youngs_modulus = " + str(L.youngs_modulus) + " Pa, expected > 0");
    check(L.poisson_ratio > -1 && L.poisson_ratio < 0.5,
          "tissue layer \"" + L.name + "\": poisson_ratio = " + str(L.poisson_ratio) + ", expected (-1, 0.5)");
  }
  const int n0 = static_cast<int>(mesh.nodes.size());
  const std::vector<const Eigen::Matrix3d*> own = own_edges(mesh);
  for (size_t e = 0; e < mesh.tets.size(); ++e) {
    const auto& t = mesh.tets[e];
    // (Messages are built only on failure: building them for every element took 2 s at 300k tetrahedra.)
    for (int a : t)
      if (a < 0 || a >= n0)
        throw InvalidInput("tissue mesh: tetrahedron " + str(e) + " has node index " + str(a) + " outside [0, " +
                           str(n0) + ")");
    if (mesh.tet_layer[e] < 0 || mesh.tet_layer[e] >= static_cast<int>(mesh.layers.size()))
      throw InvalidInput("tissue mesh: tetrahedron " + str(e) + " has layer " + str(mesh.tet_layer[e]) +
                         " but the mesh has " + str(mesh.layers.size()) + " layers");
    // The corners of its reference shape: its nodes', or its own edges from the origin.
    std::array<Eigen::Vector3d, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = reference_corner(own[e], i, mesh.nodes[t[i]]);
    const double v = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6;
    double lmax = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) lmax = std::max(lmax, (p[i] - p[j]).norm());
    if (!(v > 1e-10 * lmax * lmax * lmax))
      throw InvalidInput("tissue mesh: tetrahedron " + str(e) + " is " + (v < 0 ? "inverted" : "degenerate") +
                         " (volume " + str(v) + " m^3, longest edge " + str(lmax) + " m)");
  }
}

namespace {

// Quadratic tetrahedra: one mid-edge node per edge, numbered after the corners in the order of the sorted edge keys,
// and the corners as the coarse level.
void add_mid_edge_nodes(const mesh::TetMesh& mesh, FunctionSpace& fs) {
  const int n0 = static_cast<int>(mesh.nodes.size());
  const size_t ne = mesh.tets.size();
  fs.corners.nodes = n0;
  fs.corners.tets = mesh.tets;
  fs.corners.interpolation.resize(static_cast<size_t>(n0));
  for (int a = 0; a < n0; ++a) fs.corners.interpolation[static_cast<size_t>(a)] = mesh::NodeInterpolation::at_node(a);
  std::vector<std::pair<int64_t, int>> edge_keys;  // (key, tet*6+k)
  edge_keys.reserve(ne * 6);
  for (size_t e = 0; e < ne; ++e)
    for (int k = 0; k < 6; ++k) {
      int a = mesh.tets[e][tet_edges[k][0]], b = mesh.tets[e][tet_edges[k][1]];
      if (a > b) std::swap(a, b);
      edge_keys.emplace_back(static_cast<int64_t>(a) * n0 + b, static_cast<int>(e * 6 + k));
    }
  std::sort(edge_keys.begin(), edge_keys.end());
  int64_t prev = -1;
  int id = n0 - 1;
  for (const auto& [key, slot] : edge_keys) {
    if (key != prev) {
      ++id;
      prev = key;
      const int a = static_cast<int>(key / n0), b = static_cast<int>(key % n0);
      fs.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
      fs.corners.interpolation.push_back(mesh::NodeInterpolation::edge_midpoint(a, b));
    }
    fs.connectivity[static_cast<size_t>(slot / 6) * 10 + 4 + slot % 6] = id;
  }
}

// Every element's quadrature (weights and shape-function gradients), Lamé constants and volume, the nodes' largest
// Young's modulus, and the mean modulus and element size.
void element_data(const mesh::TetMesh& mesh, FunctionSpace& fs) {
  const int nn = fs.nodes_per_element, nq = fs.points;
  const size_t ne = mesh.tets.size();
  fs.elements.resize(ne);
  fs.lame.resize(ne);
  fs.volumes.resize(ne);
  fs.gradients.resize(ne * nq * 3 * nn);
  fs.weights.resize(ne * nq);
  fs.node_youngs_modulus.assign(fs.nodes.size(), 0.0);
  double vol_sum = 0, e_sum = 0;
  const std::vector<const Eigen::Matrix3d*> own = own_edges(mesh);
  if (!mesh.own_reference.empty()) fs.initial_gradient.assign(ne, Eigen::Matrix3d::Identity());
  for (size_t e = 0; e < ne; ++e) {
    std::vector<Eigen::Vector3d> x(static_cast<size_t>(nn));
    fs.elements[e].assign(fs.connectivity.begin() + e * nn, fs.connectivity.begin() + (e + 1) * nn);
    for (int a = 0; a < nn; ++a) x[a] = reference_corner(own[e], a, fs.nodes[fs.connectivity[e * nn + a]]);
    if (own[e]) {  // F_r = [the nodes' edges] * edges^-1: F = F_r + u ∇N^T is then the deformed edges times edges^-1
      Eigen::Matrix3d nodal;
      const int* corner = &fs.connectivity[e * nn];
      for (int i = 0; i < 3; ++i) nodal.col(i) = fs.nodes[corner[i + 1]] - fs.nodes[corner[0]];
      fs.initial_gradient[e] = nodal * own[e]->inverse();
    }
    const auto geo = element_geometry(x);
    for (int q = 0; q < nq; ++q) {
      fs.weights[e * nq + q] = geo.weights[q];
      std::copy(geo.gradients[q].data(), geo.gradients[q].data() + 3 * nn, &fs.gradients[(e * nq + q) * 3 * nn]);
    }
    const auto& layer = mesh.layers[mesh.tet_layer[e]];
    fs.lame[e] = lame_constants(layer.youngs_modulus, layer.poisson_ratio);
    fs.volumes[e] = geo.volume;
    vol_sum += geo.volume;
    e_sum += layer.youngs_modulus * geo.volume;
    for (int a = 0; a < nn; ++a) {
      double& node_e = fs.node_youngs_modulus[fs.connectivity[e * nn + a]];
      node_e = std::max(node_e, layer.youngs_modulus);
    }
  }
  fs.mean_youngs_modulus = e_sum / vol_sum;
  fs.mean_element_size = std::cbrt(6 * std::sqrt(2.0) * vol_sum / ne);
}

// The elements' data in the colouring's order (each colour's elements contiguous) for the threaded assembly.
void assembly_order(FunctionSpace& fs) {
  const int nn = fs.nodes_per_element;
  fs.colouring = element_colouring(fs.connectivity, nn, fs.nodes);
  const auto append = [](auto& to, const auto& from, size_t e, size_t per_element) {
    to.insert(to.end(), from.begin() + static_cast<std::ptrdiff_t>(e * per_element),
              from.begin() + static_cast<std::ptrdiff_t>((e + 1) * per_element));
  };
  const size_t gradients_per_element = static_cast<size_t>(fs.points * 3 * nn);
  for (const int element : fs.colouring.elements) {
    const size_t e = static_cast<size_t>(element);
    append(fs.assembly.connectivity, fs.connectivity, e, static_cast<size_t>(nn));
    append(fs.assembly.gradients, fs.gradients, e, gradients_per_element);
    append(fs.assembly.weights, fs.weights, e, static_cast<size_t>(fs.points));
    if (!fs.initial_gradient.empty()) fs.assembly.initial_gradient.push_back(fs.initial_gradient[e]);
  }
}

}  // namespace

FunctionSpace function_space(const mesh::TetMesh& mesh, ElementOrder order) {
  FunctionSpace fs;
  const int nn = fs.nodes_per_element = order == ElementOrder::Quadratic ? 10 : 4;
  fs.points = nn == 4 ? 1 : 4;
  fs.box_min = fs.box_max = mesh.nodes[0];
  for (const auto& p : mesh.nodes) {
    fs.box_min = fs.box_min.cwiseMin(p);
    fs.box_max = fs.box_max.cwiseMax(p);
  }
  if (nn == 10 && !mesh.own_reference.empty())
    throw InvalidInput("tissue mesh: tetrahedra with their own reference shape (a rezoned mesh) need linear elements");
  fs.nodes = mesh.nodes;
  const size_t ne = mesh.tets.size();
  fs.connectivity.resize(ne * nn);
  for (size_t e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a) fs.connectivity[e * nn + a] = mesh.tets[e][a];
  if (nn == 10) add_mid_edge_nodes(mesh, fs);
  element_data(mesh, fs);
  assembly_order(fs);
  return fs;
}

}  // namespace needlekit::fem::detail
