// Private to src/geometry: the vertices and faces a surface file declares, before they are checked to form a
// triangle mesh (triangle_mesh_reader.cpp), and the PLY and OFF readers that produce them.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <string_view>
#include <vector>

namespace needlekit::geometry::detail {

struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;             // file units
  std::vector<std::vector<std::int64_t>> polygons;  // 0-based vertex indices as written (not yet range-checked)
};

// ASCII, binary little- and big-endian PLY 1.0: the `vertex` element's x, y, z (any numeric type) and the `face`
// element's vertex_indices / vertex_index list (any integer type); other elements and properties are skipped.
// Every declared count is checked against the bytes left in the file before anything is allocated. Throws IoError
// naming `source_name` and, in the header, the line.
PolygonSoup read_ply_soup(std::string_view bytes, std::string_view source_name);

// ASCII OFF with the optional ST, C, N and 4 prefixes (texture coordinates, colours, normals and homogeneous
// coordinates: only x, y, z (/w) are kept; colours after a face's indices are ignored); `#` comments. Binary OFF
// and nOFF are refused. Counts are checked against the file's size before anything is allocated. Throws IoError
// naming `source_name` and the line.
PolygonSoup read_off_soup(std::string_view bytes, std::string_view source_name);

}  // namespace needlekit::geometry::detail
