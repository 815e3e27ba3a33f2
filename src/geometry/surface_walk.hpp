// Internal: the triangle-to-triangle walk shared by straightest_geodesic and cutting_plane_trace. A WalkRule says
// how the direction continues across an edge and through a vertex; the walk does the rest (exits, boundary,
// degenerate triangles, step limit, the path record).
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/geometry/geodesic_trace.hpp"

namespace needlekit::geometry::detail {

// The triangles around a vertex in counter-clockwise order (seen from outside). For a boundary vertex the list
// runs from the clockwise-most triangle to the counter-clockwise-most one.
struct FanWedge {
  int triangle = -1;
  int corner = -1;     // the vertex's corner in `triangle`
  double angle = 0;    // rad, the triangle's interior angle at the vertex
};
struct Fan {
  std::vector<FanWedge> wedges;
  bool closed = false;
  double total_angle = 0;  // rad
  int index_of(int triangle) const;
  double angle_before(int index) const;  // rad, the sum of the angles of the wedges before `index`
};
Fan fan_around(const SurfaceMesh& surface, int triangle, int corner);

// The counter-clockwise angle (rad) of `direction` (projected onto the triangle's plane) from the wedge's first
// edge (corner -> corner+1); in (-pi, pi].
double angle_in_wedge(const SurfaceMesh& surface, int triangle, int corner, const Eigen::Vector3d& direction);
// The unit direction at angle `angle` from the wedge's first edge, kept strictly inside the wedge.
Eigen::Vector3d direction_in_wedge(const SurfaceMesh& surface, const FanWedge& wedge, double angle);
// The wedge holding the direction at `angle` (rad) counter-clockwise from the fan's first edge (wrapped for a
// closed fan) and the angle within that wedge; empty if it falls off an open fan.
std::optional<std::pair<int, double>> wedge_at(const Fan& fan, double angle);

// The direction `d` (unit, in from's plane) carried across edge `edge` of `from` into `next` by unfolding: the
// angle to the shared edge is kept (Polthier & Schmies 1998), so the path is straight in the unfolded strip.
Eigen::Vector3d unfolded_direction(const SurfaceMesh& surface, int from, int edge, int next, const Eigen::Vector3d& d);

struct DirectionIn {
  int triangle = -1;
  Eigen::Vector3d direction;
};

class WalkRule {
public:
  virtual ~WalkRule() = default;
  // The direction in `next` after leaving `from` across its edge `edge` with direction `d` (unit, in from's plane).
  virtual Eigen::Vector3d across_edge(const SurfaceMesh& surface, int from, int edge, int next,
                                      const Eigen::Vector3d& d) const = 0;
  // How the path leaves the fan's vertex, arriving in fan.wedges[arrival] with direction d; empty with `reason`
  // set when it cannot go on.
  virtual std::optional<DirectionIn> through_vertex(const SurfaceMesh& surface, const Fan& fan, int arrival,
                                                    const Eigen::Vector3d& d, std::string& reason) const = 0;
  // How a path that starts at the fan's vertex in fan.wedges[start] with direction d leaves it.
  virtual std::optional<DirectionIn> leave_vertex(const SurfaceMesh& surface, const Fan& fan, int start,
                                                  const Eigen::Vector3d& d, std::string& reason) const = 0;
};

// Validates and normalises a start location; throws InvalidInput.
SurfaceLocation checked_location(const SurfaceMesh& surface, const SurfaceLocation& location, const char* what);
// Walks `length` from `start` with direction `direction` (unit, in the start triangle's plane).
SurfacePath walk(const SurfaceMesh& surface, const SurfaceLocation& start, const Eigen::Vector3d& direction,
                 double length, const WalkRule& rule, const TraceOptions& options);

}  // namespace needlekit::geometry::detail
