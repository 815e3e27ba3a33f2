// ParaView output: VTK XML unstructured grids (.vtu) and time series (.pvd). Any mix of vertices, lines, triangles
// and linear or quadratic tetrahedra, with named point and cell fields (scalars or 3-vectors or 3x3 tensors stored
// as 9 components). Written to a temporary name and renamed when complete.
#pragma once
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace needlekit::io {

enum class VtkCellType { Vertex = 1, Line = 3, Triangle = 5, Tetra = 10, QuadraticTetra = 24 };

struct VtuField {
  std::string name;            // with its unit, e.g. "von_mises_stress_Pa"
  int components = 1;          // 1, 3 or 9
  std::vector<double> values;  // size = components * (points or cells)
};

struct VtuGrid {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> cells;   // point indices per cell
  std::vector<VtkCellType> cell_types;   // one per cell
  std::vector<VtuField> point_fields;
  std::vector<VtuField> cell_fields;
};

// The .vtu document of the grid; `path` names the file in messages. Throws InvalidInput if a field's size does not
// match.
std::string vtu_document(const VtuGrid& grid, const std::filesystem::path& path);
// Writes the grid (write_file_atomically). Throws IoError naming the file, InvalidInput as vtu_document.
void write_vtu(const VtuGrid& grid, const std::filesystem::path& path);

// Writes a ParaView collection: one (time, file) entry per step, file names relative to the .pvd's folder.
struct PvdEntry {
  double time = 0;
  std::filesystem::path file;
};
// The text with & < > " as XML (and HTML) entities, for attribute values and text.
std::string xml_escaped(const std::string& text);

std::string pvd_document(const std::vector<PvdEntry>& entries);
void write_pvd(const std::vector<PvdEntry>& entries, const std::filesystem::path& path);

}  // namespace needlekit::io
