// Point location in a tetrahedral mesh: the tetrahedron that contains a point and the point's barycentric
// coordinates in it, through a Boost.Geometry R-tree of the tetrahedra's bounding boxes (bulk-loaded once).
// Used to interpolate between two meshes of the same body (coarse_level.hpp, the rezoning of
// insertion/rezoning.hpp). The mesh is any set of node positions, e.g. a deformed configuration.
#pragma once
#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

namespace needlekit::mesh {

struct TetLocation {
  int tet = -1;                       // the tetrahedron (index into the located mesh's tets)
  Eigen::Vector4d barycentric = Eigen::Vector4d::Zero();  // of the point in it, summing to 1 (negative ones: the point is outside)
  bool inside() const { return barycentric.minCoeff() >= -kInsideTolerance; }
  static constexpr double kInsideTolerance = 1e-9;  // barycentric rounding that still counts as inside
};

class TetLocator {
public:
  // Keeps references to neither argument. Throws InvalidInput for an empty tetrahedron list.
  TetLocator(const std::vector<Eigen::Vector3d>& nodes, const std::vector<std::array<int, 4>>& tets);
  ~TetLocator();
  TetLocator(TetLocator&&) noexcept;
  TetLocator& operator=(TetLocator&&) noexcept;

  // The tetrahedron the point is most inside of (the largest smallest barycentric coordinate) among those whose
  // bounding box holds it, ties to the lowest index; a point in no box takes the best of the 8 nearest boxes. On a
  // shared face or edge either neighbour may be returned. Thread-safe.
  TetLocation locate(const Eigen::Vector3d& point) const;

private:
  struct Tree;
  std::vector<Eigen::Vector3d> nodes_;
  std::vector<std::array<int, 4>> tets_;
  std::unique_ptr<Tree> tree_;
  double slack_ = 0;  // m: a point on a face or an edge is inside both neighbours' boxes
};

}  // namespace needlekit::mesh
