// The VTU/PVD files are read back by an independent reader (Debian's python3-meshio) and every point, cell and
// field value must come back exactly; a bad field size is an InvalidInput naming the field; nothing partial is left.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/vtu_writer.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Reads `file` with meshio and returns its contents as JSON (points, cell blocks, point and cell data, each field
// as rows of components).
nlohmann::json read_with_meshio(const std::filesystem::path& file) {
  const auto script = file.parent_path() / "read_back.py";
  std::ofstream(script) << R"(import json, sys, meshio
m = meshio.read(sys.argv[1])
print(json.dumps({
  "points": m.points.tolist(),
  "cells": [[b.type, b.data.tolist()] for b in m.cells],
  "point_data": {k: v.reshape(len(v), -1).tolist() for k, v in m.point_data.items()},
  "cell_data": {k: [a.reshape(len(a), -1).tolist() for a in v] for k, v in m.cell_data.items()},
}))
)";
  const std::string command = "/usr/bin/python3 " + script.string() + " " + file.string() + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run python3");
  std::string out;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = ::pclose(pipe);
  if (status != 0) throw std::runtime_error("meshio failed: " + out);
  return nlohmann::json::parse(out);
}

// Two tetrahedra sharing a face, a triangle on their boundary and a line, with scalar, vector and tensor fields.
io::VtuGrid sample_grid() {
  io::VtuGrid g;
  g.points = {{0, 0, 0}, {1e-3, 0, 0}, {0, 1e-3, 0}, {0, 0, 1e-3}, {0.4e-3, 0.4e-3, -1e-3}};
  g.cells = {{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 3}, {3, 4}};
  g.cell_types = {io::VtkCellType::Tetra, io::VtkCellType::Tetra, io::VtkCellType::Triangle,
                  io::VtkCellType::Line};
  io::VtuField displacement{"displacement_m", 3, {}};
  for (int i = 0; i < 15; ++i) displacement.values.push_back(1e-7 * i - 3.25e-7);
  g.point_fields = {displacement, {"temperature_K", 1, {300, 301.5, 302, 303.25, 1e-300}}};
  io::VtuField stress{"stress_Pa", 9, {}};
  for (int i = 0; i < 36; ++i) stress.values.push_back(0.1 * i * i - 7);
  g.cell_fields = {{"layer", 1, {0, 2, 1, 1}}, stress};
  return g;
}

}  // namespace

TEST(VtuWriter, MeshioReadsBackEveryValue) {
  const auto dir = fresh_directory("needlekit-vtu");
  const auto file = dir / "grid.vtu";
  const io::VtuGrid g = sample_grid();
  io::write_vtu(g, file);
  const nlohmann::json m = read_with_meshio(file);

  ASSERT_EQ(m["points"].size(), g.points.size());
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m["points"][i][k].get<double>(), g.points[i][k]);
  }
  // meshio groups consecutive cells of one type into a block: tetra (2), triangle (1), line (1).
  ASSERT_EQ(m["cells"].size(), 3u);
  EXPECT_EQ(m["cells"][0][0], "tetra");
  EXPECT_EQ(m["cells"][1][0], "triangle");
  EXPECT_EQ(m["cells"][2][0], "line");
  std::vector<std::vector<int>> cells;
  for (const auto& block : m["cells"]) {
    for (const auto& c : block[1]) cells.push_back(c.get<std::vector<int>>());
  }
  EXPECT_EQ(cells, g.cells);

  for (const io::VtuField& f : g.point_fields) {
    const auto& values = m["point_data"][f.name];
    ASSERT_EQ(values.size(), g.points.size()) << f.name;
    for (std::size_t p = 0; p < g.points.size(); ++p) {
      for (int c = 0; c < f.components; ++c) {
        const double read = values[p][c].get<double>();
        EXPECT_EQ(read, f.values[p * f.components + c]) << f.name << " point " << p;
      }
    }
  }
  for (const io::VtuField& f : g.cell_fields) {
    const auto& blocks = m["cell_data"][f.name];
    ASSERT_EQ(blocks.size(), 3u) << f.name;
    std::size_t cell = 0;
    for (const auto& block : blocks) {
      for (const auto& value : block) {
        for (int c = 0; c < f.components; ++c) {
          const double read = value[c].get<double>();
          EXPECT_EQ(read, f.values[cell * f.components + c]) << f.name << " cell " << cell;
        }
        ++cell;
      }
    }
    EXPECT_EQ(cell, g.cells.size());
  }
  std::filesystem::remove_all(dir);
}

TEST(VtuWriter, QuadraticTetraHasTenNodes) {
  const auto dir = fresh_directory("needlekit-vtu10");
  io::VtuGrid g;
  g.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {.5, 0, 0},
              {.5, .5, 0}, {0, .5, 0}, {0, 0, .5}, {.5, 0, .5}, {0, .5, .5}};
  g.cells = {{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}};
  g.cell_types = {io::VtkCellType::QuadraticTetra};
  io::write_vtu(g, dir / "q.vtu");
  const nlohmann::json m = read_with_meshio(dir / "q.vtu");
  ASSERT_EQ(m["cells"].size(), 1u);
  EXPECT_EQ(m["cells"][0][0], "tetra10");
  EXPECT_EQ(m["cells"][0][1][0].get<std::vector<int>>(), g.cells[0]);
  std::filesystem::remove_all(dir);
}

TEST(VtuWriter, PvdListsEveryStep) {
  const auto dir = fresh_directory("needlekit-pvd");
  io::write_pvd({{0.0, "step_0000.vtu"}, {2.5e-5, "steps/step_0001.vtu"}}, dir / "run.pvd");
  std::ifstream in(dir / "run.pvd");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_THAT(text.str(), HasSubstr("type=\"Collection\""));
  EXPECT_THAT(text.str(), HasSubstr("timestep=\"0\" group=\"\" part=\"0\" file=\"step_0000.vtu\""));
  EXPECT_THAT(text.str(), HasSubstr("timestep=\"2.5000000000000001e-05\" group=\"\" part=\"0\" "
                                    "file=\"steps/step_0001.vtu\""));
  std::filesystem::remove_all(dir);
}

TEST(VtuWriter, BadFieldSizeNamesTheFieldAndLeavesNoFile) {
  const auto dir = fresh_directory("needlekit-vtu-bad");
  io::VtuGrid g = sample_grid();
  g.cell_fields[1].values.pop_back();
  try {
    io::write_vtu(g, dir / "bad.vtu");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr("stress_Pa"));
    EXPECT_THAT(e.what(), HasSubstr("35 values; expected 36"));
  }
  g = sample_grid();
  g.cells[3] = {3, 9};
  EXPECT_THROW(io::write_vtu(g, dir / "bad.vtu"), InvalidInput);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  EXPECT_THROW(io::write_vtu(sample_grid(), dir / "missing" / "x.vtu"), IoError);
  std::filesystem::remove_all(dir);
}

TEST(VtuWriter, MeshioReadsBackWhenBase64AndRawOffsetsCoincide) {
  // meshio rewrites raw offsets into base64 ones in place and looks each raw offset up in document order: with four
  // 24-byte cell blocks, the 4th block's base64 offset (3 x 32) equals the raw offset of the points (4 x 24), which
  // broke the reading of a 102,419-element tissue mesh (8 x 102,419 + 8 is divisible by 3).
  const auto dir = fresh_directory("needlekit-vtu-offsets");
  io::VtuGrid g;
  g.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}};
  g.cells = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  g.cell_types = {io::VtkCellType::Tetra, io::VtkCellType::Tetra};
  for (int f = 0; f < 4; ++f) g.cell_fields.push_back({"field_" + std::to_string(f), 1, {f + 0.5, f + 1.5}});
  io::write_vtu(g, dir / "grid.vtu");
  const nlohmann::json m = read_with_meshio(dir / "grid.vtu");
  ASSERT_EQ(m["points"].size(), 5u);
  EXPECT_EQ(m["points"][4][2].get<double>(), -1.0);
  EXPECT_EQ(m["cell_data"]["field_3"][0][1][0].get<double>(), 4.5);
  std::filesystem::remove_all(dir);
}
