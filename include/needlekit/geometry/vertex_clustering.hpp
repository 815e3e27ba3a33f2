// Decimation of a triangle mesh by vertex clustering (Rossignac & Borrel 1993, "Multi-resolution 3D approximations
// for rendering complex scenes", Modeling in Computer Graphics, pp. 455-465): the bounding box is cut into cubic
// cells, all vertices of a cell are replaced by one representative, and a triangle is kept when its three corners
// fall into three different cells (duplicates of a kept triangle are dropped).
//
// The representative of a cell is one of its own vertices (the one nearest to the mean of the cell's vertices), so
// that every vertex of the result is a vertex of the input: a point picked on the decimated surface names a vertex of
// the full mesh (`needlekit serve` places a patch's centre vertex that way). CGAL's edge-collapse simplification
// (Surface_mesh_simplification) places new points (edge midpoints, Lindstrom-Turk), which is why it is not used here.
#pragma once
#include <vector>

#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::geometry {

struct ClusteredMesh {
  TriangleMesh mesh;                // the decimated mesh; its vertices are vertices of the input
  std::vector<int> source_vertex;   // per vertex of `mesh`: its index in the input mesh
  double cell_size = 0;             // the input's unit, the cells' edge; 0 when the input was kept whole
};

// The input whole (the vertices that triangles use) when it has at most `max_triangles` triangles; else clustered
// on the finest grid tried (cells growing by 25 % from the size that leaves about max_triangles / 2 cells on the
// surface) whose result has at most `max_triangles` triangles. Throws InvalidInput for max_triangles < 1.
ClusteredMesh clustered_mesh(const TriangleMesh& mesh, int max_triangles);

}  // namespace needlekit::geometry
