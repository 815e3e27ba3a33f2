// The patch the patch tests fit: n × n SU-8 cylinder needles (70 µm, 400 µm long) on a square of side `width`, every
// spring 1 N/mm.
#pragma once
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/patch/patch_design.hpp"

namespace needlekit::test {

inline patch::PatchDesignOptions su8_cylinder_patch(double width, int n) {
  patch::PatchDesignOptions o;
  o.needles_u = o.needles_v = n;
  o.width_u = o.width_v = width;
  o.stiffness_u = o.stiffness_v = o.stiffness_diagonal = 1e3;
  o.needle = {needle::Shape::Cylinder, 70e-6, 70e-6, 0, 400e-6};
  o.material = materials::material_preset("su-8");
  return o;
}

}  // namespace needlekit::test
