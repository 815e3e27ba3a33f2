// Private to src/mesh: the interface between the library and its Gmsh module (libneedlekit_gmsh.so, the sources in
// src/mesh/gmsh/). Gmsh links about 100 shared libraries (OpenCASCADE, FLTK, X11, GL) whose loading and relocation
// cost every process 0.2 s before main(); the module keeps them out of the library, and gmsh_module() opens it with
// dlopen the first time a function meshes or reads a .msh file, so that commands which do not mesh never load Gmsh.
//
// The module is built by the same build as the library (a version mismatch is refused when it is opened); its entry
// points take and return only needlekit's header-only types and report errors through GmshError, so that no
// exception crosses the dlopen boundary.
#pragma once
#include <array>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh::detail {

enum class GmshErrorKind { None, InvalidInput, IoError, Failure };

struct GmshError {
  GmshErrorKind kind = GmshErrorKind::None;
  std::string message;
};

// What Gmsh read from a .msh file, before numbering and validation (msh_import.cpp).
struct MshContents {
  std::vector<TissueLayer> layers;                      // one per layer, in the order of layer_corners
  std::vector<std::vector<std::size_t>> layer_corners;  // Gmsh node tags, 4 per tetrahedron, per layer
  std::vector<std::size_t> node_tags;                   // every node of the file, with
  std::vector<double> coords;                           // its x, y, z in file units
};

// An array block's repeating cell (cell_replication.hpp): a pitch_x x pitch_y rectangle centred on the origin with
// its needles' sites, and the block's margins beyond the outermost cells (m, >= 0; 0 = none).
struct CellLayout {
  double pitch_x = 0, pitch_y = 0;
  std::vector<Eigen::Vector2d> sites;  // m, from the cell's centre
  std::vector<Eigen::Vector2d> top_row_sites;  // m, from the cell's centre: sites in the +y margin strip
  bool sites_on_corners = false;               // the sites are the cell's four corners (SiteGrid)
  double margin_left = 0, margin_right = 0, margin_bottom = 0, margin_top = 0;  // -x, +x, -y, +y
  // Only a quadrant, for a cell that is its own mirror image (mirrored_cell.hpp): [0, pitch_x/2] x [0, pitch_y/2] with
  // one site on its corner at the origin and, along each axis, the margin piece beyond it ([pitch/2, pitch/2 + m],
  // piece 2; none when m = 0), m the axis' larger margin for a site at the cell's centre, half a pitch less for sites
  // on the corners (whose margin beyond the needles begins with the half cell beyond them). No periodic faces: the
  // mirror images match.
  bool quadrant = false;
};

// The cell with the margins around it (up to 3 x 3 pieces: margin, cell, margin in x and in y), its opposite side
// faces meshed periodically (the +x face a translated copy of the -x face, +y of -y), and each tetrahedron's piece.
struct CellBlockMesh {
  TetMesh mesh;              // in m, the cell centred on the origin; not yet reoriented
  std::vector<int> piece;    // per tet: 3 * py + px, px (py) = 0 the -x (-y) margin, 1 the cell, 2 the +x (+y) margin
};

// A closed, outward-oriented triangulated surface whose inside is meshed anew (mesh/surface_refill.hpp).
struct SurfaceToFill {
  std::vector<Eigen::Vector3d> nodes;         // m
  std::vector<std::array<int, 3>> triangles;  // into nodes
  std::function<double(const Eigen::Vector3d&)> size;  // m, the tetrahedra's edge length wanted at a point inside
};

struct GmshModule {
  const char* version;  // NEEDLEKIT_VERSION of the build that made the module
  // The layered block's tetrahedra (layered_block_mesh.hpp), in m, not yet reoriented. Sets `error` on failure.
  TetMesh (*layered_block)(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                           GmshError& error);
  // The array cell and its margins (CellBlockMesh), meshed on one thread with the block options' sizes and layers.
  CellBlockMesh (*cell_block)(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                              const CellLayout& layout, GmshError& error);
  // The tetrahedra and physical volume groups of `file`, matched to `layers` as MshImportOptions::layers says.
  MshContents (*read_msh)(const std::string& file, const std::vector<TissueLayer>& layers, GmshError& error);
  // The inside of `surface` as tetrahedra by Delaunay 3D on one thread, in m, not yet reoriented and with no layers:
  // the surface's nodes first, in order (its triangles are the mesh's boundary faces, none moved or split), then the
  // new ones inside.
  TetMesh (*refill)(const SurfaceToFill& surface, GmshError& error);
};

// The module, opened on the first call (thread-safe). Throws std::runtime_error naming every place it looked when
// it cannot be opened or was built by another version.
const GmshModule& gmsh_module();

// Held around every call into the module, so that read_msh_isolated never forks while another thread is inside
// Gmsh (its child would inherit Gmsh's lock held).
std::mutex& gmsh_call_mutex();

// Throws the exception `error` describes (InvalidInput, IoError or std::runtime_error); returns if there is none.
void throw_if_failed(const GmshError& error);

}  // namespace needlekit::mesh::detail

// The module's one exported symbol.
extern "C" const needlekit::mesh::detail::GmshModule* needlekit_gmsh_module_v1();
