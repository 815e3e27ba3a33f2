// mesh::LayeredBlockOptions' parameter table (core/parameter.hpp): one row per number or flag, declared here once;
// the defaults are the struct's initializers (layered_block_mesh.hpp). Case files write the rows of group "tissue"
// in [tissue] and those of "mesh" in [mesh] (`needlekit tissue-mesh`, `indent`, `insert`); the rows of no group are
// set by the commands or from Python only. The tissue reader, the commands' --help, `needlekit describe`,
// docs/reference.md and Python's LayeredBlockOptions read this table; tests/unit/test_parameter_tables.cpp checks
// that every field has a row.
//
// A new parameter: its field with its initializer in LayeredBlockOptions, and one row here.
#pragma once
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"

namespace needlekit::mesh {

inline constexpr std::tuple kLayeredBlockParameters{
    // [tissue]
    Parameter<LayeredBlockOptions, double>{"width", &LayeredBlockOptions::width, 0, kNoLimit, Bound::Open,
                                           Bound::Open, "the block's extent in x (centred on x = 0)", "tissue",
                                           units::Dimension::Length},
    Parameter<LayeredBlockOptions, double>{"length", &LayeredBlockOptions::length, 0, kNoLimit, Bound::Open,
                                           Bound::Open, "the block's extent in y (centred on y = 0)", "tissue",
                                           units::Dimension::Length},
    // [mesh]
    Parameter<LayeredBlockOptions, double>{"size_at_tip", &LayeredBlockOptions::size_at_site, 0, kNoLimit,
                                           Bound::Open, Bound::Open, "target element size at each insertion site",
                                           "mesh", units::Dimension::Length, "size_at_site"},
    Parameter<LayeredBlockOptions, double>{"refinement_radius", &LayeredBlockOptions::refinement_radius, 0, kNoLimit,
                                           Bound::Open, Bound::Open,
                                           "radius around a site where the size is size_at_tip", "mesh",
                                           units::Dimension::Length},
    Parameter<LayeredBlockOptions, double>{"size_far", &LayeredBlockOptions::size_far, 0, kNoLimit, Bound::Open,
                                           Bound::Open, "element size far from the sites (at least size_at_tip)",
                                           "mesh", units::Dimension::Length},
    Parameter<LayeredBlockOptions, double>{"size_gradient", &LayeredBlockOptions::size_gradient, 0, kNoLimit,
                                           Bound::Open, Bound::Open,
                                           "growth of the element size per unit distance outside the refinement "
                                           "radius and thin layers (0.3: 30 um per 100 um)",
                                           "mesh"},
    Parameter<LayeredBlockOptions, double>{"thin_layer_size_factor", &LayeredBlockOptions::thin_layer_size_factor, 0,
                                           kNoLimit, Bound::Closed, Bound::Open,
                                           "the element size inside a layer is capped at this times its thickness "
                                           "(0: no cap)",
                                           "mesh"},
    Parameter<LayeredBlockOptions, double>{"site_circle_radius", &LayeredBlockOptions::site_circle_radius, 0,
                                           kNoLimit, Bound::Closed, Bound::Open,
                                           "a circle of this radius around each site is embedded in the top surface "
                                           "(nodes on a flat punch's edge; 0: none)",
                                           "mesh", units::Dimension::Length},
    Flag<LayeredBlockOptions>{"split", &LayeredBlockOptions::split,
                              "mesh at twice the sizes, then split every tet into eight: the coarse level of the "
                              "two-grid solver",
                              "mesh"},
    Parameter<LayeredBlockOptions, double>{"max_tetrahedra", &LayeredBlockOptions::max_tetrahedra, 1, kNoLimit,
                                           Bound::Closed, Bound::Open,
                                           "a block whose estimated tetrahedron count exceeds this is refused before "
                                           "meshing",
                                           "mesh"},
    // set by the commands (--threads, the solver's choice) or from Python
    Parameter<LayeredBlockOptions, int>{"threads", &LayeredBlockOptions::threads, 0, kNoLimit, Bound::Closed,
                                        Bound::Closed,
                                        "Gmsh threads (0: one, and the same mesh bit for bit in every run)"},
    Flag<LayeredBlockOptions>{"coarse_level", &LayeredBlockOptions::coarse_level,
                              "also return a coarse level for the FE's two-grid solver"},
    Parameter<LayeredBlockOptions, double>{"coarse_size_factor", &LayeredBlockOptions::coarse_size_factor, 1,
                                           kNoLimit, Bound::Open, Bound::Open,
                                           "the coarse level's sizes over this mesh's (coarse_level without split)"},
};
// Fields that are not parameters: layers (a list of TissueLayer, read from [tissue] preset or [[tissue.layers]]) and
// insertion_sites (a list of points, [mesh] sites).
inline constexpr std::size_t kLayeredBlockListFields = 2;
static_assert(field_count<LayeredBlockOptions>() ==
                  std::tuple_size_v<decltype(kLayeredBlockParameters)> + kLayeredBlockListFields,
              "a field of LayeredBlockOptions has no row in kLayeredBlockParameters (or a row too many)");

}  // namespace needlekit::mesh
