// VTK XML UnstructuredGrid (.vtu) with raw appended binary data (UInt64 block headers, little endian): no base64
// or compression cost on writing, and read directly by ParaView/VTK and meshio. PVD collections list the step
// files. Everything is assembled in memory and written atomically (temporary name + rename).
#include "needlekit/io/vtu_writer.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/atomic_file.hpp"

namespace needlekit::io {
namespace {

static_assert(std::endian::native == std::endian::little, "the VTU writer declares byte_order=\"LittleEndian\"");

int nodes_of(VtkCellType type) {
  switch (type) {
    case VtkCellType::Vertex: return 1;
    case VtkCellType::Line: return 2;
    case VtkCellType::Triangle: return 3;
    case VtkCellType::Tetra: return 4;
    case VtkCellType::QuadraticTetra: return 10;
  }
  return -1;
}

// One DataArray of the appended section: its XML attributes and its bytes.
struct AppendedArray {
  const char* type;
  std::string name;
  int components;
  const void* data;
  std::uint64_t bytes;
};

template <class T>
AppendedArray appended(const char* type, std::string name, int components, const T* data, std::size_t count) {
  return {type, std::move(name), components, data, count * sizeof(T)};
}

void check_field(const VtuField& field, std::size_t entities, const char* kind, const std::filesystem::path& path) {
  if (field.components != 1 && field.components != 3 && field.components != 9) {
    throw InvalidInput(fmt::format("{}: {} field \"{}\" has {} components; expected 1, 3 or 9", path.string(), kind,
                                   field.name, field.components));
  }
  if (field.values.size() != entities * static_cast<std::size_t>(field.components)) {
    throw InvalidInput(fmt::format("{}: {} field \"{}\" has {} values; expected {} ({} {}s x {} components)",
                                   path.string(), kind, field.name, field.values.size(),
                                   entities * field.components, entities, kind, field.components));
  }
}

std::string data_array_xml(const AppendedArray& a, std::uint64_t offset) {
  return fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
                     "offset=\"{}\"/>\n",
                     a.type, xml_escaped(a.name), a.components, offset);
}

}  // namespace

std::string vtu_document(const VtuGrid& grid, const std::filesystem::path& path) {
  const std::size_t points = grid.points.size();
  const std::size_t cells = grid.cells.size();
  if (grid.cell_types.size() != cells) {
    throw InvalidInput(fmt::format("{}: {} cell types for {} cells; expected one type per cell", path.string(),
                                   grid.cell_types.size(), cells));
  }
  std::vector<std::int64_t> connectivity;
  std::vector<std::int64_t> offsets(cells);
  std::vector<std::uint8_t> types(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    const int expected = nodes_of(grid.cell_types[c]);
    if (expected < 0 || static_cast<int>(grid.cells[c].size()) != expected) {
      throw InvalidInput(fmt::format("{}: cell {} has {} points; its VTK type {} needs {}", path.string(), c,
                                     grid.cells[c].size(), static_cast<int>(grid.cell_types[c]), expected));
    }
    for (int p : grid.cells[c]) {
      if (p < 0 || static_cast<std::size_t>(p) >= points) {
        throw InvalidInput(fmt::format("{}: cell {} refers to point {}; the grid has {} points", path.string(), c, p,
                                       points));
      }
      connectivity.push_back(p);
    }
    offsets[c] = static_cast<std::int64_t>(connectivity.size());
    types[c] = static_cast<std::uint8_t>(grid.cell_types[c]);
  }
  for (const VtuField& f : grid.point_fields) check_field(f, points, "point", path);
  for (const VtuField& f : grid.cell_fields) check_field(f, cells, "cell", path);

  // The arrays in document order: point fields, cell fields, points, connectivity, offsets, types.
  std::vector<AppendedArray> arrays;
  for (const VtuField& f : grid.point_fields) {
    arrays.push_back(appended("Float64", f.name, f.components, f.values.data(), f.values.size()));
  }
  const std::size_t first_cell_field = arrays.size();
  for (const VtuField& f : grid.cell_fields) {
    arrays.push_back(appended("Float64", f.name, f.components, f.values.data(), f.values.size()));
  }
  const std::size_t points_array = arrays.size();
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
  arrays.push_back(appended("Float64", "Points", 3, grid.points.empty() ? nullptr : grid.points.front().data(),
                            3 * points));
  arrays.push_back(appended("Int64", "connectivity", 1, connectivity.data(), connectivity.size()));
  arrays.push_back(appended("Int64", "offsets", 1, offsets.data(), offsets.size()));
  arrays.push_back(appended("UInt8", "types", 1, types.data(), types.size()));

  // The appended blocks (UInt64 byte count + bytes) go in reverse document order: meshio converts raw offsets to
  // base64 ones in place and finds each raw offset by the first DataArray in document order that has it, which
  // picks an already converted array when a base64 offset equals a later raw offset (see the VtuWriter tests).
  std::vector<std::uint64_t> offset(arrays.size());
  std::uint64_t total = 0;
  for (std::size_t k = arrays.size(); k-- > 0;) {
    offset[k] = total;
    total += sizeof(std::uint64_t) + arrays[k].bytes;
  }

  std::string xml = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
      points, cells);
  for (std::size_t k = 0; k < arrays.size(); ++k) {
    if (k == 0) xml += "      <PointData>\n";
    if (k == first_cell_field) xml += "      </PointData>\n      <CellData>\n";
    if (k == points_array) xml += "      </CellData>\n      <Points>\n";
    if (k == points_array + 1) xml += "      </Points>\n      <Cells>\n";
    xml += data_array_xml(arrays[k], offset[k]);
  }
  xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  const std::size_t data_start = xml.size();
  xml.resize(data_start + total);
  for (std::size_t k = arrays.size(); k-- > 0;) {
    char* at = xml.data() + data_start + offset[k];
    std::memcpy(at, &arrays[k].bytes, sizeof(std::uint64_t));
    if (arrays[k].bytes > 0) std::memcpy(at + sizeof(std::uint64_t), arrays[k].data, arrays[k].bytes);
  }
  xml += "\n  </AppendedData>\n</VTKFile>\n";
  return xml;
}

void write_vtu(const VtuGrid& grid, const std::filesystem::path& path) {
  write_file_atomically(path, vtu_document(grid, path));
}

std::string pvd_document(const std::vector<PvdEntry>& entries) {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const PvdEntry& e : entries) {
    xml += fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                       xml_escaped(e.file.generic_string()));
  }
  xml += "  </Collection>\n</VTKFile>\n";
  return xml;
}

void write_pvd(const std::vector<PvdEntry>& entries, const std::filesystem::path& path) {
  write_file_atomically(path, pvd_document(entries));
}


std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace needlekit::io
