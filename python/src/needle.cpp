// needlekit/needle and needlekit/materials: needle geometry, sections, surface meshes, needle materials and tissue
// layer presets.
#include "common.hpp"
#include "enum_binding.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/needle/needle_geometry.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "needlekit/needle/section_properties.hpp"

namespace needlekit::python {

void bind_needle(py::module_& m) {
  using needle::NeedleGeometry;
  using needle::Shape;
  bind_enum<needle::kShapeNames>(m, "Shape", "Needle shape (dissertation §4.3-4.5).");
  m.def("shape_from_string", &needle::shape_from_string, py::arg("text"), py::arg("what") = "shape",
        "\"cylinder\", \"cone\" or \"bevel\".");

  py::class_<NeedleGeometry> geometry(m, "NeedleGeometry",
                                      "One microneedle: axis z, base at z = 0, tip at z = L (metres).");
  def_keyword_init<NeedleGeometry>(geometry);
  geometry.def_property(
      "shape", [](const NeedleGeometry& g) { return g.shape; },
      [](NeedleGeometry& g, py::handle value) {
        g.shape = py::isinstance<py::str>(value) ? needle::shape_from_string(value.cast<std::string>(), "shape")
                                                 : value.cast<Shape>();
      },
      "Shape or \"cylinder\" | \"cone\" | \"bevel\"");
  def_quantity(geometry, "tip_diameter", &NeedleGeometry::tip_diameter, Dimension::Length,
               "m, D1 > 0 (bevel: the sagitta of the tip's circular segment; cylinder: D1 == D2)");
  def_quantity(geometry, "base_diameter", &NeedleGeometry::base_diameter, Dimension::Length, "m, D2 >= D1");
  def_quantity(geometry, "bore_diameter", &NeedleGeometry::bore_diameter, Dimension::Length,
               "m, D3 in [0, D1): 0 is a solid needle");
  def_quantity(geometry, "length", &NeedleGeometry::length, Dimension::Length, "m, L > 0");
  geometry.def_property_readonly("hollow", &NeedleGeometry::hollow, "bore_diameter > 0");

  m.def(
      "validate_needle", [](const NeedleGeometry& g, const std::string& where) { needle::validate(g, where); },
      py::arg("needle"), py::arg("where") = "needle", "Raises InvalidInput naming the field of an invalid needle.");
  m.def("tip_area", &needle::tip_area, py::arg("needle"), "Interfacial (tip) area A, m^2 (§4.2).");
  m.def("outer_diameter_at", &needle::outer_diameter_at, py::arg("needle"), py::arg("distance_from_tip"),
        "Outer diameter (m) at a distance (m) from the tip.");
  m.def("volume", &needle::volume, py::arg("needle"), "Volume of needle material (bore removed), m^3.");

  py::class_<needle::SectionProperties>(m, "SectionProperties", "Cross-section of a needle (SI).")
      .def_readonly("area", &needle::SectionProperties::area, "m^2, material area")
      .def_readonly("centroid_offset", &needle::SectionProperties::centroid_offset, "m (bevel only)")
      .def_readonly("second_moment_min", &needle::SectionProperties::second_moment_min, "m^4")
      .def_readonly("second_moment_max", &needle::SectionProperties::second_moment_max, "m^4")
      .def_readonly("section_modulus_min", &needle::SectionProperties::section_modulus_min, "m^3");
  m.def("section_at", &needle::section_at, py::arg("needle"), py::arg("distance_from_tip"),
        "Section at a distance (m) from the tip.");

  py::class_<needle::NeedleMeshOptions> mesh_options(m, "NeedleMeshOptions", "Segments of a needle's surface mesh.");
  def_keyword_init<needle::NeedleMeshOptions>(mesh_options);
  mesh_options.def_readwrite("circumferential_segments", &needle::NeedleMeshOptions::circumferential_segments, ">= 8")
      .def_readwrite("axial_segments", &needle::NeedleMeshOptions::axial_segments, ">= 1");
  m.def("needle_surface_mesh", &needle::needle_surface_mesh, py::arg("needle"),
        py::arg("options") = needle::NeedleMeshOptions{},
        "Closed, outward-oriented TriangleMesh of the needle (m, needle frame).");

  using materials::NeedleMaterial;
  py::class_<NeedleMaterial> material(m, "NeedleMaterial", "A needle material with the sources of its values.");
  def_keyword_init<NeedleMaterial>(material);
  material.def_readwrite("name", &NeedleMaterial::name);
  def_quantity(material, "youngs_modulus", &NeedleMaterial::youngs_modulus, Dimension::Pressure, "Pa, E > 0");
  def_optional_quantity(material, "yield_strength", &NeedleMaterial::yield_strength, Dimension::Pressure,
                        "Pa, s_y or None");
  def_optional_quantity(material, "allowable_stress", &NeedleMaterial::allowable_stress, Dimension::Pressure,
                        "Pa, sigma of Eqs 5.7/5.8 or None");
  material.def_readwrite("source", &NeedleMaterial::source);
  m.def("material_preset_names", &materials::material_preset_names, "The needle material presets.");
  m.def("material_preset", &materials::material_preset, py::arg("name"), py::arg("what") = "material",
        "A needle material preset by name (case-insensitive).");

  using materials::TissueLayer;
  py::class_<TissueLayer> layer(m, "TissueLayer", "One tissue layer and its linear-elastic constants (SI).");
  def_keyword_init<TissueLayer>(layer);
  layer.def_readwrite("name", &TissueLayer::name);
  def_quantity(layer, "thickness", &TissueLayer::thickness, Dimension::Length, "m, > 0");
  def_quantity(layer, "youngs_modulus", &TissueLayer::youngs_modulus, Dimension::Pressure, "Pa, > 0");
  layer.def_readwrite("poisson_ratio", &TissueLayer::poisson_ratio, "(-1, 0.5)");
  py::class_<materials::TissuePreset>(m, "TissuePreset", "Tissue layers with their sources.")
      .def_readonly("name", &materials::TissuePreset::name)
      .def_readonly("layers", &materials::TissuePreset::layers)
      .def_readonly("height", &materials::TissuePreset::height, "m")
      .def_readonly("source", &materials::TissuePreset::source);
  m.def("tissue_preset_names", &materials::tissue_preset_names);
  m.def("tissue_preset", &materials::tissue_preset, py::arg("name"), py::arg("what") = "tissue preset");
  m.def("skin_layers", &materials::skin_layers, py::arg("stratum_corneum_modulus") = 100e6,
        "The dissertation's three skin layers (§3.3.2); stratum_corneum_modulus in Pa.");
}

}  // namespace needlekit::python
