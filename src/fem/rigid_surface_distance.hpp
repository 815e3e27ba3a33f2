// Internal: signed distance to a closed, outward-oriented triangle mesh (a rigid needle) with the gradient direction,
// by the closest feature and its angle-weighted pseudo-normal (Bærentzen & Aanæs, IEEE TVCG 11(3), 2005). Brute
// force over the triangles whose bounding boxes are within reach of the query; needle meshes are small.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::fem::detail {

struct SignedDistance {
  double distance = 0;      // m, negative inside
  Eigen::Vector3d normal;   // unit, outward: gradient of the signed distance
};

class RigidSurfaceDistance {
public:
  explicit RigidSurfaceDistance(const geometry::TriangleMesh& mesh);
  // Signed distance of q, or a positive value >= `reach` (normal undefined) when q is farther than `reach`.
  SignedDistance signed_distance(const Eigen::Vector3d& q, double reach) const;
  const Eigen::Vector3d& box_min() const { return lo_; }
  const Eigen::Vector3d& box_max() const { return hi_; }

private:
  std::vector<Eigen::Vector3d> v_;
  std::vector<std::array<int, 3>> t_;
  std::vector<Eigen::Vector3d> face_normal_, vertex_normal_;
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normal_;  // per triangle edge k = (k, k+1)
  std::vector<Eigen::Vector3d> tri_lo_, tri_hi_;
  Eigen::Vector3d lo_, hi_;
};

}  // namespace needlekit::fem::detail
