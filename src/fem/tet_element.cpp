#include "needlekit/fem/tet_element.hpp"

#include <Eigen/LU>
#include <stdexcept>

#include "tet_kernel.hpp"

namespace needlekit::fem {

ElementGeometry element_geometry(const std::vector<Eigen::Vector3d>& x) {
  const int n = static_cast<int>(x.size());
  if (n != 4 && n != 10) throw std::invalid_argument("element_geometry: 4 or 10 nodes expected");
  const auto quad = detail::tet_quadrature(n);
  ElementGeometry geo;
  geo.nodes = n;
  // Barycentric -> reference coordinates ξ = (L1, L2, L3), L0 = 1 - ξ1 - ξ2 - ξ3.
  Eigen::Matrix<double, 3, 4> dl_dxi;
  dl_dxi << -1, 1, 0, 0, -1, 0, 1, 0, -1, 0, 0, 1;
  for (int q = 0; q < quad.points; ++q) {
    const Eigen::MatrixXd dn_dxi = dl_dxi * detail::shape_barycentric_gradients(n, quad.barycentric[q]);  // 3 x n
    Eigen::Matrix3d jac = Eigen::Matrix3d::Zero();  // J_ij = dX_j / dξ_i
    for (int a = 0; a < n; ++a) jac += dn_dxi.col(a) * x[a].transpose();
    const double det = jac.determinant();
    geo.weights.push_back(quad.weights[q] * det);
    geo.volume += quad.weights[q] * det;
    geo.gradients.push_back(det != 0 ? Eigen::MatrixXd(jac.inverse() * dn_dxi) : Eigen::MatrixXd::Zero(3, n));
  }
  return geo;
}

namespace {
template <int N>
ElementResponse response_fixed(const ElementGeometry& geo, MaterialLaw law, const LameConstants& lame,
                               const Eigen::VectorXd& displacement, bool with_tangent) {
  std::vector<detail::Grad<N>> grads(geo.gradients.begin(), geo.gradients.end());
  const Eigen::Matrix<double, 3, N> u = Eigen::Map<const Eigen::Matrix<double, 3, N>>(displacement.data());
  Eigen::Matrix<double, 3, N> f;
  Eigen::Matrix<double, 3 * N, 3 * N> k;
  ElementResponse r;
  r.valid = detail::tet_kernel<N>(grads.data(), geo.weights.data(), static_cast<int>(grads.size()), law, lame, u,
                                  r.energy, f, with_tangent ? &k : nullptr);
  r.force = Eigen::Map<const Eigen::VectorXd>(f.data(), 3 * N);
  if (with_tangent) r.tangent = k;
  return r;
}
}  // namespace

ElementResponse element_response(const ElementGeometry& geo, MaterialLaw law, const LameConstants& lame,
                                 const Eigen::VectorXd& displacement, bool with_tangent) {
  if (displacement.size() != 3 * geo.nodes) throw std::invalid_argument("element_response: 3 * nodes displacements");
  return geo.nodes == 4 ? response_fixed<4>(geo, law, lame, displacement, with_tangent)
                        : response_fixed<10>(geo, law, lame, displacement, with_tangent);
}

}  // namespace needlekit::fem
