// The 3D view of an FE indentation run (docs/views.md): the tissue's deformed boundary surface at each load step with
// displacement, von Mises stress and contact pressure per vertex, and the needles in place, as one JavaScript data
// file (NAME_view.js, io/view_page.hpp) of base64 typed arrays (io/view_arrays.hpp) that the report's viewer reads.
//
// Size: positions and fields are stored as 16-bit codes relative to their range over the run (about 12 bytes per
// surface vertex and step before base64). When the whole boundary does not fit in ViewOptions::max_bytes with two
// steps, only the top surface (z = 0, where the needles are) is kept; then load steps are dropped evenly (the last
// one always kept) until the file fits. The view says what it kept ("surface_region", "steps_total").
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/tissue_view_surface.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::io {

struct ViewOptions {
  double max_bytes = 5e6;  // bytes, > 0: the data file's budget (the 5 MB for a 300k-tetrahedron run)
};

// Records the steps of one run (call set_mesh from IndentationOptions::on_mesh and add_step from on_step), then
// writes its view.
class IndentationView {
public:
  IndentationView(const insertion::IndentationCase& indentation_case, ViewOptions options = {});
  // Again after steps were added: a rezoning of the tissue (IndentationOptions::on_mesh), whose steps are added to
  // the same surface; another mesh is a std::logic_error.
  void set_mesh(const mesh::TetMesh& tissue);
  void add_step(const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver);
  // The same from the step's values: the needles' displacement (m, along their direction), the force on each needle
  // (N) and the surface values (surface_step).
  void add_step(const insertion::IndentationStep& step, double indenter_displacement, SurfaceStep surface);

  // Each needle's outcome over the run (IndentationResult::needles, one per needle of the case, its per-step values
  // indexed as the steps added): the table then also holds, per needle, its puncture state ("status": "intact" or
  // "punctured", per step), its tip depth below the undeformed surface ("depth_um", per step), its inserted depth
  // (its travel beyond its puncture depth, "inserted_depth_um", per step, a colour), the step it punctured in
  // ("puncture_step", null when it did not) and its puncture depth.
  void set_outcomes(std::vector<insertion::NeedleOutcome> needles);

  const TissueViewSurface& surface() const { return boundary_; }
  int steps() const { return static_cast<int>(steps_.size()); }
  // The view as JSON: {"format": "needlekit-view/1", "kind": "indentation", "name", "title", "steps": [{"label",
  // "depth_um", "force_N"}], "steps_total", "surface": {"region", "vertices", "indices", "positions", "fields": [{"key",
  // "label", "unit", "scale", "values"}]}, "needles": {"meshes", "instances", "direction", "displacement_m", "table"},
  // "notes"}. Throws std::logic_error before set_mesh.
  nlohmann::json json() const;

private:
  struct Step {
    insertion::IndentationStep step;
    double indenter_displacement = 0;
    SurfaceStep surface;
  };
  const insertion::IndentationCase& case_;
  ViewOptions options_;
  mesh::TetMesh tissue_;
  TissueViewSurface boundary_;
  std::vector<Step> steps_;
  std::vector<insertion::NeedleOutcome> outcomes_;
  nlohmann::json needles_json(const std::vector<int>& kept) const;
};

}  // namespace needlekit::io
