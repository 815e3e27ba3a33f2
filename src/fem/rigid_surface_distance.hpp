// Internal: signed distance to a closed, outward-oriented triangle mesh (a rigid needle) with the gradient direction,
// by the closest feature and its angle-weighted pseudo-normal (Bærentzen & Aanæs, IEEE TVCG 11(3), 2005). Brute
// force over the triangles whose bounding boxes are within reach of the query; needle meshes are small.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::fem::detail {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5), with the feature:
// 0..2 vertex, 3..5 edge (k-3) = (k, k+1), 6 face.
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, int& feature);

struct SignedDistance {
  double distance = 0;      // m, negative inside
  Eigen::Vector3d normal;   // unit, outward: gradient of the signed distance
  // 1/m, the signed distance's Hessian: zero nearest a face; nearest an edge of unit direction e at the distance r
  // from the core, +-(I - n n^T - e e^T) / r (+ outside the core, - inside), nearest a vertex +-(I - n n^T) / r (the
  // distance to a line or a point). Only where the point lies in the rounding shell (r > offset / 2): nearer the
  // core's sharp features it is left zero, as it is without an offset.
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

class RigidSurfaceDistance {
public:
  // `direction`: the needle's direction of motion. Triangles whose outward normal points along it (n . direction >
  // kLeadingCosine) are the needle's leading faces, the ones that can push tissue ahead of the needle.
  // `offset` >= 0: distances are to the set of points within `offset` of the mesh (the mesh is a needle's eroded
  // core, Indenter::edge_radius): the mesh's distance minus `offset`, with the same gradient direction.
  RigidSurfaceDistance(const geometry::TriangleMesh& mesh, const Eigen::Vector3d& direction, double offset = 0);
  // Signed distance of q, or a positive value >= `reach` (normal undefined) when q is farther than `reach`.
  // With `ahead` (a node that was ahead of the needle, under its leading faces, at the last converged state), inside
  // the needle the distance and normal are those to the nearest point of the leading faces (the way out that the
  // needle's motion defines), not to the nearest point of the whole surface: a tissue node under a thin tip (a sharp
  // bevel's tip segment, a rim) is otherwise closest to a side wall once the needle has moved by more than half the
  // tip's width, gets a horizontal normal and is pushed sideways with zero force along the needle while the needle
  // slides past it.
  SignedDistance signed_distance(const Eigen::Vector3d& q, double reach, bool ahead = false) const;
  static constexpr double kLeadingCosine = 1e-3;
  // The body's bounding box (the mesh's, grown by the offset).
  const Eigen::Vector3d& box_min() const { return lo_; }
  const Eigen::Vector3d& box_max() const { return hi_; }
  // m, Indenter::edge_radius: > 0 gives the distance a curvature (SignedDistance::hessian).
  double offset() const { return offset_; }

private:
  struct Nearest {
    double squared_distance = 0;  // m^2; reach^2 when no triangle is nearer
    int triangle = -1;            // -1: none within reach
    int feature = 6;              // closest_on_triangle's feature: 0..2 vertex, 3..5 edge, 6 face
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
  };
  // The nearest point of the triangles in `subset` (all when null) to q, within `reach`.
  Nearest nearest(const Eigen::Vector3d& q, double reach, const std::vector<int>* subset) const;
  // SignedDistance::hessian at q for its nearest point `n` at the distance `dist` (> 0) from the core, `sign` +1
  // outside and -1 inside.
  Eigen::Matrix3d feature_hessian(const Eigen::Vector3d& q, const Nearest& n, double dist, double sign) const;

  std::vector<Eigen::Vector3d> v_;
  std::vector<std::array<int, 3>> t_;
  std::vector<Eigen::Vector3d> face_normal_, vertex_normal_;
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normal_;  // per triangle edge k = (k, k+1)
  std::vector<Eigen::Vector3d> tri_lo_, tri_hi_;
  std::vector<int> leading_;  // indices of the leading triangles
  Eigen::Vector3d lo_, hi_;
  double offset_ = 0;
};

}  // namespace needlekit::fem::detail
