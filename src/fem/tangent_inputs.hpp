// Internal: what the quasi-static solver's tangent (tangent_matrix.hpp), its linear solves (linear_solve.hpp) and
// their preconditioners are built from: the mesh's elements, the free-dof numbering, the nodal volume average and
// the coarse level.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "needlekit/mesh/coarse_level.hpp"

namespace needlekit::fem::detail {

class NodalVolumeAverage;

// What the tangent and its solves are built from (all kept by reference: they must outlive the solver).
struct TangentInputs {
  const std::vector<int>& connectivity;    // nodes_per_element node indices per element
  int nodes_per_element = 4;               // 4 or 10
  int node_count = 0;
  const std::vector<Eigen::Vector3d>& nodes;  // m, the reference positions (the PETSc backend's rigid-body modes)
  const std::vector<int>& free_index;      // per dof: its free index, or -1 if prescribed
  // Every element once, in the order the assembly visits them (ElementColouring::elements); the slot table is stored
  // in that order, so the assembly reads it front to back.
  const std::vector<int>& assembly_order;
  const NodalVolumeAverage* nodal = nullptr;   // the nodal volume average of linear elements, or null
  const mesh::CoarseLevel* coarse = nullptr;   // the two-grid solve's coarse level, or null
};

}  // namespace needlekit::fem::detail
