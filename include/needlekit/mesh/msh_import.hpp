// Import of a user's tetrahedral Gmsh mesh (.msh, any version Gmsh reads): its physical volume groups become the
// tissue layers. Gmsh stays in the Gmsh module (src/mesh/gmsh/,
// opened on the first call).
#pragma once
#include <filesystem>
#include <vector>

#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

struct MshImportOptions {
  double unit = 1.0;                 // m per file length unit, > 0 (1e-6 for a file in um, 1e-3 for mm)
  std::vector<TissueLayer> layers;   // the layers, matched by name to the file's physical volume groups; their
                                     // thicknesses are not used. Empty: one layer per physical volume group, named
                                     // after it, with youngs_modulus = 0 for the caller to set. A file without
                                     // named physical volumes is accepted when exactly one layer is given.
  bool reorient = false;             // true: left-handed tetrahedra are renumbered right-handed; false: they are an
                                     // error (a mesh with inverted elements)
  bool keep_reader_process = false;  // true: the child process that runs Gmsh's reader (so that a crash of Gmsh's
                                     // on a malformed file cannot take the program down) stays for the next import
                                     // instead of being started for each file: for many imports in a row (fuzzing,
                                     // batch scripts). A child that crashed is replaced. It holds a copy-on-write
                                     // image of the program as it was when it started.
  double reader_cpu_limit = 0;       // s of CPU time the reader's child may spend on one file, >= 0 (0: no limit);
                                     // a file that needs more is refused by name (InvalidInput). For fuzzing: some
                                     // malformed files make Gmsh's reader loop over a count read from garbage
};

struct MshImportResult {
  TetMesh mesh;                       // 10-node tetrahedra keep their 4 corner nodes
  std::vector<LayerQuality> quality;  // one per layer
  int reoriented = 0;                 // left-handed tetrahedra renumbered (reorient = true)
};

// Throws IoError naming the file if it cannot be read, and InvalidInput naming the file for: a mesh without
// tetrahedra, a named layer without a physical volume group (listing the groups the file has), tetrahedra in no
// layer or in two, inverted (reorient = false) or degenerate tetrahedra with their indices.
MshImportResult msh_import(const std::filesystem::path& file, const MshImportOptions& options = {});

}  // namespace needlekit::mesh
