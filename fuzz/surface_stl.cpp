// The Stl surface reader, then the body-surface checks and index that `surface` and `patch` run on what it read.
#include "fuzz_target.hpp"
#include "surface_checks.hpp"

NEEDLEKIT_FUZZ_TARGET(surface_stl) {
  needlekit::fuzz::refusals_allowed([&] {
    needlekit::fuzz::check_surface(
        needlekit::geometry::parse_triangle_mesh(bytes, needlekit::geometry::MeshFormat::Stl, "fuzz.stl", 1e-3));
  });
}
