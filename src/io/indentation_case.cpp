#include "needlekit/io/indentation_case.hpp"

#include "needlekit/fem/parallel_session.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/io/force_curve_csv.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/insertion/loading_parameters.hpp"
#include "needlekit/insertion/puncture_parameters.hpp"
#include "needlekit/io/toml_config.hpp"
#include "tissue_config_toml.hpp"
#include "needlekit/io/toml_parameters.hpp"

namespace needlekit::io {
namespace {

using namespace config;  // the TOML reading helpers of toml_config.hpp

double quantity_at_least_zero(const Section& section, const toml::node& node, std::string_view key,
                              Dimension dimension, std::string_view meaning) {
  const double value = quantity_of(section, node, key, dimension);
  if (!(value >= 0)) {
    section.fail(node, key, fmt::format("'{}' is negative: {}, expected a {} >= 0", node.as_string()->get(), meaning,
                                        units::dimension_name(dimension)));
  }
  return value;
}

// ---- [needle] -----------------------------------------------------------------------------------------------------

struct NeedleRead {
  geometry::TriangleMesh mesh;
  std::optional<needle::NeedleGeometry> geometry;
  needle::NeedleMeshOptions mesh_options;
  std::optional<double> edge_radius;
  double tip_height = 0;
};

NeedleRead read_needle(const Section& section, const toml::table& root, const std::filesystem::path& base) {
  NeedleRead result;
  if (const toml::node* node = section.optional("tip_height")) {
    result.tip_height = quantity_at_least_zero(section, *node, "tip_height", Dimension::Length,
                                               "the needle would start inside the tissue");
  }
  if (const toml::node* node = section.optional("edge_radius")) {
    result.edge_radius = quantity_at_least_zero(section, *node, "edge_radius", Dimension::Length, "a radius is a size");
  }
  if (const toml::node* mesh_node = section.optional("mesh")) {
    for (std::string_view key : {"shape", "tip_diameter", "base_diameter", "bore_diameter", "length", "segments",
                                 "axial_segments"}) {
      if (const toml::node* other = section.optional(key)) {
        section.fail(*other, key, "given together with mesh, expected either a needle mesh or a parametric needle");
      }
    }
    const std::string file = text_of(section, *mesh_node, "mesh", "an STL file name");
    const toml::node& unit_node = section.required("mesh_unit", "the length unit of the STL coordinates, e.g. \"um\"");
    const std::string unit_text = text_of(section, unit_node, "mesh_unit", "a length unit, e.g. \"um\"");
    const double unit =
        section.at(unit_node, [&] { return units::unit_factor(unit_text, Dimension::Length, section.what("mesh_unit")); });
    const std::filesystem::path path = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : base / file;
    result.mesh = geometry::read_stl(path, unit);
    const geometry::MeshTopologyReport topology = geometry::topology_report(result.mesh);
    if (result.mesh.triangles.empty() || !topology.closed || !topology.consistently_oriented) {
      section.fail(*mesh_node, "mesh",
                   fmt::format("'{}' is not a closed, consistently oriented surface ({} triangles, {} boundary "
                               "edges), expected a closed needle surface",
                               path.string(), result.mesh.triangles.size(), topology.boundary_edges));
    }
    if (geometry::signed_volume(result.mesh) < 0) {  // inward normals: flip to outward
      for (auto& triangle : result.mesh.triangles) std::swap(triangle[1], triangle[2]);
    }
    return result;
  }
  needle::NeedleGeometry geometry = needle_of(section);
  validate_at_keys(root, section.file(), section.table(), [&] { needle::validate(geometry, "needle"); });
  // The surface mesher's planar faces cannot be triangulated in double precision beyond these proportions (fuzzing
  // found a 5e55 um base on a 50 um tip): a needle's dimensions within a factor kMaxNeedleAspect of each other.
  constexpr double kMaxNeedleAspect = 1e6;
  for (const auto& [key, value] : {std::pair{"base_diameter", geometry.base_diameter},
                                   std::pair{"length", geometry.length}}) {
    const double smallest = std::min(geometry.tip_diameter, geometry.length);
    if (value > kMaxNeedleAspect * smallest) {
      // A cylinder may leave base_diameter out (it is the tip's): then the tip_diameter key is the one to name.
      const std::string_view named = section.optional(key) ? std::string_view(key) : std::string_view("tip_diameter");
      section.fail(*section.optional(named), named,
                   fmt::format("{:g} um is more than {:g} times the needle's smallest dimension ({:g} um), expected "
                               "a needle in proportion",
                               value * 1e6, kMaxNeedleAspect, smallest * 1e6));
    }
  }
  needle::NeedleMeshOptions mesh_options;
  if (const toml::node* node = section.optional("segments")) {
    mesh_options.circumferential_segments = integer_in(section, *node, "segments", 8, limits::kMaxNeedleSegments);
  }
  if (const toml::node* node = section.optional("axial_segments")) {
    mesh_options.axial_segments = integer_in(section, *node, "axial_segments", 1, limits::kMaxNeedleSegments);
  }
  if (const long long quads = static_cast<long long>(mesh_options.circumferential_segments) *
                              mesh_options.axial_segments;
      quads > limits::kMaxNeedleSegments * 64LL) {
    section.fail(section.optional("segments") ? *section.optional("segments") : *section.optional("axial_segments"),
                 "segments",
                 fmt::format("{} x {} axial segments make {} quadrilaterals, more than needlekit's work limit of {}",
                             mesh_options.circumferential_segments, mesh_options.axial_segments, quads,
                             limits::kMaxNeedleSegments * 64LL));
  }
  result.mesh = needle::needle_surface_mesh(geometry, mesh_options);
  result.geometry = geometry;
  result.mesh_options = mesh_options;
  return result;
}

std::vector<insertion::NeedleSite> read_sites(const Section& top, double default_tip_height,
                                             const std::vector<Eigen::Vector2d>& mesh_sites) {
  const toml::node* node = top.optional("needles");
  if (!node) {  // one needle at each [mesh] site (default: one at the centre)
    std::vector<insertion::NeedleSite> sites;
    for (const Eigen::Vector2d& p : mesh_sites) sites.push_back({p, default_tip_height});
    return sites;
  }
  if (!node->is_array_of_tables() || node->as_array()->empty()) {
    top.fail(*node, "needles", fmt::format("{} is not an array of tables, expected [[needles]] entries with x, y",
                                           describe(*node)));
  }
  std::vector<insertion::NeedleSite> sites;
  const toml::array& array = *node->as_array();
  for (std::size_t i = 0; i < array.size(); ++i) {
    const Section entry = top.subsection(*array.get(i), fmt::format("needles[{}]", i), {"x", "y", "tip_height"});
    insertion::NeedleSite site;
    site.tip_height = default_tip_height;
    if (const toml::node* x = entry.optional("x")) site.position.x() = quantity_of(entry, *x, "x", Dimension::Length);
    if (const toml::node* y = entry.optional("y")) site.position.y() = quantity_of(entry, *y, "y", Dimension::Length);
    if (const toml::node* h = entry.optional("tip_height")) {
      site.tip_height = quantity_at_least_zero(entry, *h, "tip_height", Dimension::Length,
                                               "the needle would start inside the tissue");
    }
    sites.push_back(site);
  }
  return sites;
}

// ---- [array] ------------------------------------------------------------------------------------------------------

insertion::NeedleArray read_array(const Section& section) {
  insertion::NeedleArray array;
  if (const toml::node* node = section.optional("layout")) {
    array.layout = choice_of(section, *node, "layout", insertion::kArrayLayoutNames);
  }
  for (const auto& parameter : insertion::kArrayCounts) {  // declared once in needle_array.hpp
    if (const toml::node* node = section.optional(parameter.key)) {
      array.*parameter.field = integer_in(section, *node, parameter.key, static_cast<int>(parameter.min),
                                          static_cast<int>(parameter.max));
    }
  }
  for (const auto& parameter : insertion::kArrayLengths) {
    if (const toml::node* node = section.optional(parameter.key)) {
      const double value = quantity_of(section, *node, parameter.key, Dimension::Length);
      if (!parameter.accepts(value)) {
        section.fail(*node, parameter.key,
                     fmt::format("{} is out of range, expected a length {} m", describe(*node), parameter.range()));
      }
      array.*parameter.field = value;
    }
  }
  if (const toml::node* node = section.optional("backing_plate")) {
    array.backing_plate = boolean_of(section, *node, "backing_plate");
  }
  if (const toml::node* node = section.optional("symmetry")) {
    array.symmetry = choice_of(section, *node, "symmetry", insertion::kArraySymmetryNames);
  }
  return array;
}

// The case's needles and block from [array]: every needle of the array at [needle]'s tip height; unless [tissue]
// gives them, the block's width and length are the footprint plus the margin on every side.
void apply_array(const toml::table& root, const Section& top, const Section& section, double tip_height,
                 insertion::IndentationCase& c) {
  if (const toml::node* needles = top.optional("needles")) {
    top.fail(*needles, "needles", "given together with [array], expected the needles in one of them");
  }
  if (const toml::node* sites = root.at_path("mesh.sites").node()) {
    top.fail(*sites, "mesh.sites", "given together with [array], expected the needles in one of them");
  }
  const insertion::NeedleArray array = read_array(section);
  validate_at_keys(root, section.file(), section.table(), [&] { insertion::validate(array, insertion::base_diameter(c)); });
  insertion::set_array(c, array, tip_height, !root.at_path("tissue.width").node(), !root.at_path("tissue.length").node());
}

// ---- the rest -----------------------------------------------------------------------------------------------------

// [solver]: the rows of fem::kSolverParameters in group "solver", then the checks between them. Into c.solver; c's
// tissue tells whether the nodal-averaged volume applies to any of its layers.
void read_solver(const Section& section, insertion::IndentationCase& c) {
  fem::SolverOptions& solver = c.solver;
  read_parameters(section, fem::kSolverParameters, "solver", solver);
  if (const toml::node* node = section.optional("backend")) {
    if (!fem::backend_compiled(solver.backend)) {
      section.fail(*node, "backend",
                   fmt::format("\"{}\" is not in this build, expected {} (PETSc: configure with "
                               "-DNEEDLEKIT_WITH_PETSC=ON)",
                               fem::to_string(solver.backend), fem::compiled_backend_names()));
    }
  }
  if (const toml::node* node = section.optional("volumetric_stabilization")) {  // not silently ignored either
    if (!fem::nodal_average_possible(solver)) {
      section.fail(*node, "volumetric_stabilization",
                   "applies only to the nodal-averaged volume (law = \"neo-hookean\", element = \"linear\", "
                   "volumetric = \"auto\" or \"nodal-average\"); remove it");
    }
    if (!insertion::uses_nodal_average(c)) {  // volumetric = "auto" and every layer below kNearlyIncompressible
      section.fail(*node, "volumetric_stabilization",
                   fmt::format("applies only to the nodal-averaged volume, which volumetric = \"auto\" gives layers "
                               "with poisson_ratio >= {} and no layer has one; remove it",
                               fem::kNearlyIncompressible));
    }
  }
  if (!solver.rezone) {  // settings of the rezoning: not silently ignored
    for (std::string_view key : {"rezone_volume_ratio", "max_remeshes"}) {
      if (const toml::node* node = section.optional(key))
        section.fail(*node, key, "applies only with rezone = true; remove it or set rezone = true");
    }
  }
  if (solver.contact != fem::ContactModel::Surface) {  // settings of the surface contact: not silently ignored
    for (std::string_view key : {"penalty_factor", "penetration_tolerance", "max_augmentations", "friction", "two_pass"}) {
      if (const toml::node* node = section.optional(key)) {
        section.fail(*node, key,
                     fmt::format("applies only to [model] contact = \"surface\", but contact = \"{}\"; remove it",
                                 name_of(fem::kContactModelNames, solver.contact)));
      }
    }
  }
}

// toughness_from = { first = "a.csv", second = "b.csv", crack_area = "6661 um2", min_depth?, max_depth? }: J of
// Eq 3.16 from two insertions at the same spot; the crack area defaults to the parametric needle's tip area.
double two_insertion_toughness_of(const Section& puncture, const toml::node& node,
                                  const std::optional<needle::NeedleGeometry>& geometry,
                                  const std::filesystem::path& base) {
  const Section table =
      puncture.subsection(node, "toughness_from", {"first", "second", "crack_area", "min_depth", "max_depth"});
  const auto curve = [&](std::string_view key) {
    const toml::node& file_node = table.required(key, "a CSV file with columns depth_um,force_N");
    const std::filesystem::path file = text_of(table, file_node, key, "a CSV file name");
    return table.at(file_node, [&] { return read_force_curve_csv(file.is_absolute() ? file : base / file); });
  };
  const insertion::ForceDepthCurve first = curve("first"), second = curve("second");
  insertion::ToughnessOptions options;
  if (auto area = optional_positive_quantity(table, "crack_area", Dimension::Area)) {
    options.crack_area = *area;
  } else if (geometry) {
    options.crack_area = needle::tip_area(*geometry);
  } else {
    table.fail(node, "crack_area", "missing for a needle given as a mesh, expected an area, e.g. \"6661 um2\"");
  }
  if (const toml::node* min = table.optional("min_depth")) {
    options.min_depth = quantity_at_least_zero(table, *min, "min_depth", Dimension::Length, "before the surface");
  }
  options.max_depth = optional_positive_quantity(table, "max_depth", Dimension::Length);
  return table.at(node, [&] { return insertion::two_insertion_toughness(first, second, options).toughness; });
}

// [puncture]: the rows of insertion::kPunctureParameters (the law, its material length, the optional critical
// pressure and toughness), and the toughness from two insertions (toughness_from).
void read_puncture(const Section& puncture, const std::filesystem::path& base_directory,
                   insertion::IndentationCase& result) {
  read_parameters(puncture, insertion::kPunctureParameters, "puncture", result.puncture);
  if (const toml::node* node = puncture.optional("toughness_from")) {
    if (result.puncture.toughness) {
      puncture.fail(*node, "toughness_from", "given together with toughness, expected one of them");
    }
    result.puncture.toughness = two_insertion_toughness_of(puncture, *node, result.geometry, base_directory);
  }
}

// Every needle of [[needles]] (or [mesh] sites) inside the block's top surface, at the key that placed it.
void check_sites_inside(const toml::table& root, const Section& top, const insertion::IndentationCase& result) {
  for (std::size_t i = 0; i < result.needles.size() && !result.array; ++i) {
    const Eigen::Vector2d p = result.needles[i].position;
    if (!result.tissue_mesh && !(std::abs(p.x()) < result.block.width / 2 && std::abs(p.y()) < result.block.length / 2)) {
      const toml::node& at = top.optional("needles") ? *top.optional("needles")->as_array()->get(i) : root;
      throw InvalidInput(fmt::format("{} key 'needles[{}]': ({}, {}) is outside the {} x {} block, expected "
                                     "|x| < width/2 and |y| < length/2",
                                     location(top.file(), at.source()), i, units::format(p.x(), "um"),
                                     units::format(p.y(), "um"), units::format(result.block.width, "um"),
                                     units::format(result.block.length, "um")));
    }
  }
}

}  // namespace

fem::SolverOptions case_solver_defaults() {
  fem::SolverOptions options;
  options.law = fem::MaterialLaw::NeoHookean;
  options.contact = fem::ContactModel::Surface;
  return options;
}

insertion::IndentationCase parse_indentation_case_toml(std::string_view text, std::string_view source_name,
                                                       const std::filesystem::path& base_directory) {
  const std::string file(source_name);
  const toml::table root = parse_toml(text, file);
  const Section top(root, "", file,
                    {"name", "needle", "needles", "array", "tissue", "mesh", "loading", "model", "solver", "puncture"});

  insertion::IndentationCase result;
  result.name = std::filesystem::path(file).stem().string();
  if (const toml::node* node = top.optional("name")) result.name = text_of(top, *node, "name", "a case name");
  result.solver = case_solver_defaults();

  const Section needle = top.required_subsection(
      "needle", {"shape", "tip_diameter", "base_diameter", "bore_diameter", "length", "material", "mesh", "mesh_unit",
                 "tip_height", "segments", "axial_segments", "edge_radius"});
  NeedleRead needle_read = read_needle(needle, root, base_directory);
  result.needle = std::move(needle_read.mesh);
  result.geometry = needle_read.geometry;
  result.needle_mesh = needle_read.mesh_options;
  result.edge_radius = needle_read.edge_radius;
  if (needle.optional("material")) result.material = material_of(needle, "material");
  // [tissue] and [mesh]: the reader shared with `needlekit tissue-mesh` (tissue_config.hpp).
  top.required("tissue", "a table [tissue] with a preset or [[tissue.layers]]");
  const TissueCase tissue = tissue_case_of(root, file, base_directory);
  result.block = tissue.block;
  if (!tissue.msh_file.empty()) result.tissue_mesh = tissue_mesh(tissue).mesh;
  if (top.optional("needles") && top.optional("mesh") && top.optional("mesh")->as_table() &&
      top.optional("mesh")->as_table()->get("sites")) {
    top.fail(*top.optional("mesh")->as_table()->get("sites"), "mesh.sites",
             "given together with [[needles]], expected the sites in one of them");
  }
  if (const auto array = top.optional_subsection("array", {"layout", "rows", "columns", "pitch", "margin",
                                                            "backing_plate", "symmetry"})) {
    apply_array(root, top, *array, needle_read.tip_height, result);  // the block holds the array: validate checks it
  } else {
    result.needles = read_sites(top, needle_read.tip_height, tissue.block.insertion_sites);
  }
  check_sites_inside(root, top, result);

  // [loading]: the rows of insertion::kLoadingParameters (their combinations: insertion::validate below).
  read_parameters(top.subsection(top.required("loading", "a table [loading]"), "loading",
                                 keys_of_group(insertion::kLoadingParameters, "loading")),
                  insertion::kLoadingParameters, "loading", result);
  if (const toml::node* node = top.optional("model")) {
    read_parameters(top.subsection(*node, "model", keys_of_group(fem::kSolverParameters, "model")),
                    fem::kSolverParameters, "model", result.solver);
  }
  if (const toml::node* node = top.optional("solver")) {
    read_solver(top.subsection(*node, "solver", keys_of_group(fem::kSolverParameters, "solver")), result);
  }
  std::vector<std::string_view> puncture_keys = keys_of_group(insertion::kPunctureParameters, "puncture");
  puncture_keys.push_back("toughness_from");
  if (const toml::node* node = top.optional("puncture")) {
    read_puncture(top.subsection(*node, "puncture", puncture_keys), base_directory, result);
  }
  validate_at_keys(root, file, root, [&] { insertion::validate(result); });
  return result;
}

insertion::IndentationCase read_indentation_case(const std::filesystem::path& path) {
  return parse_indentation_case_toml(read_text(path), path.string(), path.parent_path());
}

}  // namespace needlekit::io
