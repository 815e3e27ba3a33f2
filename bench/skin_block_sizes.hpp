// The default skin block's element sizes for about 100k, 300k and 1M tetrahedra, shared by the meshing
// (bench_tissue_mesh.cpp) and indentation (bench_indentation.cpp) benchmarks.
#pragma once

#include <cstddef>

#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"

namespace needlekit::bench {

struct SkinBlockSize {
  double size_at_site;       // m
  double size_far;           // m
  double refinement_radius;  // m
};

// Measured with Gmsh 4.8's Delaunay 3D (BENCHMARKS.md, eleventh session): 119k, 303k and 1.07M tetrahedra. The 100k
// size cannot come closer: the stratum corneum's cap (2 x its 20 um) alone puts ~42k tetrahedra in that layer, and
// the 300k and 1M sizes were scaled from HXT's (296k at 11 / 180 um, 1.05M at 8.5 / 125 um), for which Delaunay
// makes 16-19 % more elements.
inline constexpr SkinBlockSize kSkinBlockSizes[] = {
    {25e-6, 250e-6, 250e-6}, {11.8e-6, 193e-6, 300e-6}, {9e-6, 132e-6, 400e-6}};

// The default skin block (its layers given explicitly) at kSkinBlockSizes[size].
inline mesh::LayeredBlockOptions skin_block_options(std::size_t size) {
  mesh::LayeredBlockOptions block;
  block.layers = materials::skin_layers();
  block.size_at_site = kSkinBlockSizes[size].size_at_site;
  block.size_far = kSkinBlockSizes[size].size_far;
  block.refinement_radius = kSkinBlockSizes[size].refinement_radius;
  return block;
}

}  // namespace needlekit::bench
