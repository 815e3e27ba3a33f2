// Uses the installed library: the §6.3.1 cone's performance index (1.288e-4 /um), and a small tissue block meshed
// by the installed Gmsh module (opened on first use through the RUNPATH that find_package(needlekit) gives).
#include <needlekit/analysis/performance_index.hpp>
#include <needlekit/mesh/layered_block_mesh.hpp>
#include <needlekit/mesh/mesh_validation.hpp>

#include <cmath>
#include <cstdio>

int main() {
  needlekit::analysis::ArrayDesign design;
  design.needle = {needlekit::needle::Shape::Cone, 30e-6, 150e-6, 0.0, 500e-6};
  design.material = needlekit::materials::material_preset("silicon");
  const auto result = needlekit::analysis::performance_index(design, {});
  if (std::abs(result.performance_index * 1e-6 / 1.288e-4 - 1) >= 2e-3) return 1;

  needlekit::mesh::LayeredBlockOptions block;
  block.width = block.length = 1000e-6;
  block.layers = {{"silicone", 500e-6, 0.2e6, 0.45}};
  block.size_at_site = 100e-6;
  block.threads = 1;
  const auto meshed = needlekit::mesh::layered_block_mesh(block);
  double volume = 0;  // of the tetrahedra: the block's 1000 x 1000 x 500 um
  for (const auto& t : meshed.mesh.tets) {
    const auto& n = meshed.mesh.nodes;
    volume += needlekit::mesh::signed_volume(n[t[0]], n[t[1]], n[t[2]], n[t[3]]);
  }
  std::printf("meshed %zu tetrahedra, volume %.6g m3\n", meshed.mesh.tets.size(), volume);
  return std::abs(volume / 5e-10 - 1) < 1e-9 ? 0 : 2;
}
