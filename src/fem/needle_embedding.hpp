// Internal: how deep a rigid needle's tip lies inside the tissue, past its top surface. Node-to-surface contact
// (surface_contact.hpp) keeps the tissue's nodes out of the needle, not its faces: a tip narrower than two or three
// tissue elements (the §6.2 blunt bevel's 46 µm wide tip face) pushes the nodes under it aside and cuts between them
// into the tissue, with or without friction; frictionless, a Newton solve can then end on the far side, the tip
// inside the tissue with no node in contact and the force down to a few per cent ("tunnelling", docs/fem_solver.md).
// Those states are equilibria of the discrete problem, so Newton accepts them; this measure says so. A point of
// the needle's tip (its sharp edges and vertices within `spacing` of its lowest one along the direction of motion, on
// its eroded core, edge_radius inside the rounded surface) that lies inside a deformed tetrahedron is embedded by
// its distance to the deformed top surface; the measure is the largest such distance.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "boundary_conditions.hpp"
#include "function_space.hpp"
#include "needlekit/fem/solver_options.hpp"

namespace needlekit::fem::detail {

class NeedleEmbedding {
public:
  // `spacing`: the largest distance between the needle's points along an edge, and the height of the tip above the
  // needle's lowest point, m. `space` and `top` are kept by reference.
  NeedleEmbedding(const FunctionSpace& space, const TopSurface& top, const std::vector<Indenter>& needles,
                  double spacing);

  // The largest depth below the tissue's top surface of a tip point inside the tissue in the state (u, needle
  // displacement d), over the needles; 0 when none is inside. m.
  double deepest(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d) const;

private:
  struct NeedlePoints {
    Eigen::Vector3d direction;
    std::vector<Eigen::Vector3d> points;  // m, at zero displacement
  };
  const FunctionSpace& space_;  // its elements' first four nodes are their corners
  const TopSurface& top_;
  std::vector<NeedlePoints> needles_;
};

}  // namespace needlekit::fem::detail
