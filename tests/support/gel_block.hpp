// A 1 mm gel cube (E = 0.2 MPa, nu = 0.45) of 10 x 10 x 10 structured cells of 100 um, centred on x = y = 0 with its
// top at z = 0, as linear tetrahedra with its top surface (internal fem::detail): the block the unit tests of the
// pieces that act on the top surface (the second pass of contact, the embedded-tip measure) press on.
#pragma once
#include "../../src/fem/boundary_conditions.hpp"
#include "../../src/fem/function_space.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"

namespace needlekit::test {

struct GelBlock {
  fem::detail::FunctionSpace space;
  fem::detail::TopSurface top;
};

inline GelBlock gel_block() {
  mesh::StructuredBlockOptions o;
  o.width = o.length = o.height = 1e-3;
  o.nx = o.ny = o.nz = 10;
  o.material = {"gel", 0, 0.2e6, 0.45};
  const mesh::TetMesh mesh = mesh::structured_block_mesh(o);
  GelBlock b{fem::detail::function_space(mesh, fem::ElementOrder::Linear), {}};
  b.top = fem::detail::top_surface(mesh, b.space, 1e-9);
  return b;
}

}  // namespace needlekit::test
