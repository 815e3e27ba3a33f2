// needlekit/mesh and the tissue case files: tetrahedral tissue meshes (numpy nodes and tets), the layered block mesher
// (Gmsh) and the [tissue]/[mesh] tables of case files.
#include "common.hpp"
#include "needlekit/io/tet_mesh_vtu.hpp"
#include "needlekit/io/tissue_config.hpp"
#include "needlekit/io/vtu_writer.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/layered_block_parameters.hpp"
#include "parameters.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::python {

void bind_mesh(py::module_& m) {
  using namespace mesh;
  py::class_<TetMesh>(m, "TetMesh",
                      "A tetrahedral tissue mesh: nodes (N, 3) in m, tets (M, 4), tet_layer (M) as read-only numpy "
                      "views; layers with E and nu. Top surface z = 0, tissue below.")
      .def(py::init([](py::handle nodes, py::handle tets, py::handle tet_layer, std::vector<TissueLayer> layers) {
             TetMesh mesh;
             mesh.nodes = points_from(nodes, "nodes");
             mesh.tets = index_rows_from<4>(tets, "tets");
             for (double layer : values_from(tet_layer, "tet_layer")) mesh.tet_layer.push_back(static_cast<int>(layer));
             mesh.layers = std::move(layers);
             if (mesh.tet_layer.size() != mesh.tets.size())
               throw_invalid("tet_layer: one layer index per tet expected");
             return mesh;
           }),
           py::arg("nodes"), py::arg("tets"), py::arg("tet_layer"), py::arg("layers"))
      .def_property_readonly(
          "nodes", [](py::object self) { return points_view(self.cast<const TetMesh&>().nodes, self); }, "m, (N, 3)")
      .def_property_readonly(
          "tets", [](py::object self) { return index_view(self.cast<const TetMesh&>().tets, self); }, "(M, 4)")
      .def_property_readonly(
          "tet_layer", [](py::object self) { return values_view(self.cast<const TetMesh&>().tet_layer, self); }, "(M)")
      .def_readonly("layers", &TetMesh::layers);

  py::class_<LayeredBlockOptions> block(m, "LayeredBlockOptions",
                                        "A layered tissue block to mesh (§3.3; default 3000 x 3000 x 1150 um skin).");
  block.def_readwrite("layers", &LayeredBlockOptions::layers, "top to bottom; empty: skin_layers()")
      .def_property(
          "insertion_sites",
          [](const LayeredBlockOptions& o) {
            py::array_t<double> a({static_cast<py::ssize_t>(o.insertion_sites.size()), py::ssize_t{2}});
            for (std::size_t i = 0; i < o.insertion_sites.size(); ++i)
              for (int k = 0; k < 2; ++k) a.mutable_at(i, k) = o.insertion_sites[i][k];
            return a;
          },
          [](LayeredBlockOptions& o, py::handle v) { o.insertion_sites = points2_from(v, "insertion_sites"); },
          "m, (K, 2) sites (x, y) on the top surface");
  def_parameters<LayeredBlockOptions>(block, kLayeredBlockParameters);  // every other field, from its table
  py::class_<LayerQuality>(m, "LayerQuality")
      .def_readonly("name", &LayerQuality::name)
      .def_readonly("tets", &LayerQuality::tets)
      .def_readonly("min_quality", &LayerQuality::min_quality)
      .def_readonly("mean_quality", &LayerQuality::mean_quality);
  py::class_<LayeredBlockResult>(m, "LayeredBlockResult")
      .def_readonly("mesh", &LayeredBlockResult::mesh)
      .def_readonly("quality", &LayeredBlockResult::quality)
      .def_readonly("mesh_seconds", &LayeredBlockResult::mesh_seconds, "s");
  m.def(
      "layered_block_mesh",
      [](const LayeredBlockOptions& o) {
        py::gil_scoped_release released;
        return layered_block_mesh(o);
      },
      py::arg("options"), "Meshes the block with Gmsh (GIL released).");

  py::class_<io::TissueCase>(m, "TissueCase", "The [tissue] and [mesh] tables of a case file.")
      .def_readwrite("block", &io::TissueCase::block)
      .def_readwrite("msh_file", &io::TissueCase::msh_file)
      .def_readwrite("msh_unit", &io::TissueCase::msh_unit, "m per length unit");
  m.def("read_tissue_case", &io::read_tissue_case, py::arg("path"));
  m.def(
      "tissue_mesh",
      [](const io::TissueCase& c) {
        py::gil_scoped_release released;
        return io::tissue_mesh(c);
      },
      py::arg("tissue"), "The case's tissue mesh (meshed block or imported .msh).");
  m.def(
      "write_tet_mesh_vtu",
      [](const TetMesh& mesh, const std::string& path) { io::write_vtu(io::tet_mesh_grid(mesh), path); },
      py::arg("mesh"), py::arg("path"), "The mesh as a ParaView .vtu (layer_id, E, nu per cell).");
}

}  // namespace needlekit::python
