// The data structures of dissertation §3.3.3 (Tables 3.1 and 3.2): the triangle list of every distinct face, the
// tetrahedron -> triangle links, tetrahedron-tetrahedron adjacency through shared faces, and the boundary surface
// (faces with one tetrahedron) with its triangle-triangle adjacency.
#pragma once
#include <array>
#include <vector>

#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

// Local faces of a tetrahedron (P1, P2, P3, P4) in §3.3.3's order: (P1,P2,P3), (P2,P3,P4), (P3,P4,P1), (P4,P1,P2).
inline constexpr std::array<std::array<int, 3>, 4> kTetFaces{{{0, 1, 2}, {1, 2, 3}, {2, 3, 0}, {3, 0, 1}}};

struct TetTopology {
  std::vector<std::array<int, 3>> triangles;      // every distinct face; nodes as in its first tetrahedron
  std::vector<std::array<int, 4>> tet_triangles;  // per tet, its triangle for each local face (kTetFaces order)
  std::vector<std::array<int, 2>> triangle_tets;  // per triangle, its tetrahedra (second = -1 on the boundary)
  std::vector<std::array<int, 4>> tet_neighbors;  // Table 3.2: the tet across each local face, -1 on the boundary
  std::vector<int> boundary_triangles;            // triangles with one tetrahedron, ascending
};

// Builds the links by sorting the faces (O(n log n), deterministic). Throws InvalidInput if a face is shared by
// more than two tetrahedra (a non-manifold or overlapping mesh), naming the tetrahedra.
TetTopology tet_topology(const TetMesh& mesh);

struct BoundarySurface {
  std::vector<std::array<int, 3>> triangles;  // mesh node indices, ordered so the normal points out of the tissue
  std::vector<int> tets;                      // the tetrahedron each triangle bounds
  std::vector<std::array<int, 3>> neighbors;  // the triangle across edge (t[k], t[(k+1)%3]); -1 if that edge does
                                              // not have exactly two boundary triangles (open or non-manifold)
};

// The boundary surface of the mesh (what §3.3.3 displays instead of the tetrahedra).
BoundarySurface boundary_surface(const TetMesh& mesh, const TetTopology& topology);

// V - E + F of the surface (2 for a closed surface of genus 0, such as a block's boundary).
int euler_characteristic(const BoundarySurface& surface);

}  // namespace needlekit::mesh
