#include "needlekit/io/indentation_view.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "needlekit/io/view_arrays.hpp"

namespace needlekit::io {
namespace {

constexpr double kBase64 = 4.0 / 3.0;
// Bytes of one surface vertex per stored step: x y z and three fields as 16-bit codes.
constexpr double kBytesPerVertexStep = 6 * 2;
// The needles, the table and the JSON around the arrays.
constexpr double kOverheadBytes = 64e3;

struct FieldSpec {
  const char* key;
  const char* label;
  const char* unit;
  double scale;  // from SI to the displayed unit
  std::vector<float> SurfaceStep::*values;
};
const FieldSpec kFields[] = {
    {"displacement_m", "displacement", "um", 1e6, &SurfaceStep::displacement},
    {"von_mises_stress_Pa", "von Mises stress", "kPa", 1e-3, &SurfaceStep::von_mises_stress},
    {"contact_pressure_Pa", "contact pressure", "kPa", 1e-3, &SurfaceStep::contact_pressure},
};

double surface_bytes(const TissueViewSurface& surface, std::size_t steps) {
  return kBase64 * (12.0 * surface.triangles.size() + kBytesPerVertexStep * surface.nodes.size() * steps);
}

// `count` step indices out of `total`, evenly spread, the last one always kept.
std::vector<int> kept_steps(int total, int count) {
  std::vector<int> kept;
  if (total <= 0) return kept;
  count = std::clamp(count, 1, std::max(total, 1));
  for (int k = 0; k < count; ++k) {
    const int index = total - 1 - static_cast<int>(std::floor(static_cast<double>(k) * total / count));
    if (kept.empty() || kept.back() != index) kept.push_back(index);
  }
  std::reverse(kept.begin(), kept.end());
  return kept;
}

// The columns of a needle's outcome (IndentationView::set_outcomes), in the order append_outcome writes them.
const nlohmann::json kOutcomeColumns = nlohmann::json::array(
    {{{"key", "status"}, {"label", "puncture state"}, {"unit", ""}, {"per_step", true}},
     {{"key", "depth_um"}, {"label", "tip depth"}, {"unit", "um"}, {"per_step", true}},
     {{"key", "inserted_depth_um"}, {"label", "inserted depth"}, {"unit", "um"}, {"per_step", true}, {"colour", true}},
     {{"key", "puncture_step"}, {"label", "punctured at step"}, {"unit", ""}},
     {{"key", "puncture_depth_um"}, {"label", "puncture depth"}, {"unit", "um"}}});

// A needle's outcome at the stored steps `kept` (indices of the run's converged steps), appended to its table row.
// Its inserted depth at a step is its travel beyond its puncture depth once punctured (insertion::NeedleOutcome's
// inserted_depth at the last step), else 0.
void append_outcome(nlohmann::json& row, const insertion::NeedleOutcome& outcome, const std::vector<int>& kept) {
  nlohmann::json state = nlohmann::json::array(), depth = nlohmann::json::array(), inserted = nlohmann::json::array();
  for (int k : kept) {
    const bool punctured = outcome.puncture_step > 0 && outcome.puncture_step <= k + 1;  // puncture_step counts from 1
    state.push_back(punctured ? "punctured" : "intact");
    if (k >= static_cast<int>(outcome.depth.size())) {
      depth.push_back(nullptr);
      inserted.push_back(nullptr);
      continue;
    }
    depth.push_back(outcome.depth[k] * 1e6);
    const double puncture_depth = outcome.puncture ? outcome.puncture->depth : outcome.depth[k];
    inserted.push_back(punctured ? std::max(outcome.depth[k] - puncture_depth, 0.0) * 1e6 : 0.0);
  }
  row.push_back(state);
  row.push_back(depth);
  row.push_back(inserted);
  row.push_back(outcome.puncture_step > 0 ? nlohmann::json(outcome.puncture_step) : nlohmann::json(nullptr));
  row.push_back(outcome.puncture ? nlohmann::json(outcome.puncture->depth * 1e6) : nlohmann::json(nullptr));
}

std::vector<float> floats(const Eigen::Vector3d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

}  // namespace

IndentationView::IndentationView(const insertion::IndentationCase& indentation_case, ViewOptions options)
    : case_(indentation_case), options_(options) {}

void IndentationView::set_mesh(const mesh::TetMesh& tissue) {
  if (!steps_.empty()) {
    // A rezoned mesh (IndentationOptions::on_mesh): the same boundary faces, their nodes kept in the same order
    // (at the same reference positions), so the steps recorded so far keep their surface and the next ones sample
    // the new mesh there.
    std::size_t next = 0;
    for (int& node : boundary_.nodes) {
      const Eigen::Vector3d& position = tissue_.nodes[static_cast<std::size_t>(node)];
      while (next < tissue.nodes.size() && tissue.nodes[next] != position) ++next;
      if (next == tissue.nodes.size())
        throw std::logic_error("view: a new mesh after the first step must be a rezoning of the tissue");
      node = static_cast<int>(next++);
    }
    tissue_ = tissue;
    return;
  }
  tissue_ = tissue;
  boundary_ = tissue_view_surface(tissue_);
}

void IndentationView::add_step(const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
  const fem::ElementFields fields = solver.element_fields();
  add_step(step, solver.indenter_displacement(),
           surface_step(boundary_, tissue_, solver.displacement(), solver.contact_pressure(), fields.von_mises_stress));
}

void IndentationView::set_outcomes(std::vector<insertion::NeedleOutcome> needles) { outcomes_ = std::move(needles); }

void IndentationView::add_step(const insertion::IndentationStep& step, double indenter_displacement,
                               SurfaceStep surface) {
  steps_.push_back({step, indenter_displacement, std::move(surface)});
}

nlohmann::json IndentationView::json() const {
  if (boundary_.nodes.empty()) throw std::logic_error("IndentationView::json before set_mesh");
  const int total = steps();
  // The whole boundary if it fits with two steps (or the run's one), else the top surface; then as many steps as fit.
  const double budget = options_.max_bytes - kOverheadBytes;
  const std::size_t minimum_steps = std::min<std::size_t>(2, std::max(total, 1));
  const bool whole = surface_bytes(boundary_, minimum_steps) <= budget;
  const TissueViewSurface top = whole ? TissueViewSurface{} : top_surface(boundary_, tissue_);
  const TissueViewSurface& shown = whole ? boundary_ : top;
  const double per_step = kBase64 * kBytesPerVertexStep * shown.nodes.size();
  const int fitting = static_cast<int>(std::floor((budget - surface_bytes(shown, 0)) / std::max(per_step, 1.0)));
  const std::vector<int> kept = kept_steps(total, fitting);

  // Surface vertex of `shown` -> its index in the boundary's vertex list (both ascending by mesh node).
  std::vector<std::size_t> source(shown.nodes.size());
  for (std::size_t v = 0, b = 0; v < shown.nodes.size(); ++v) {
    while (boundary_.nodes[b] != shown.nodes[v]) ++b;
    source[v] = b;
  }
  std::vector<float> positions;
  positions.reserve(3 * shown.nodes.size() * kept.size());
  for (int k : kept) {
    for (std::size_t b : source) {
      for (int c = 0; c < 3; ++c) positions.push_back(steps_[k].surface.positions[3 * b + c]);
    }
  }
  nlohmann::json fields = nlohmann::json::array();
  for (const FieldSpec& spec : kFields) {
    std::vector<float> values;
    values.reserve(shown.nodes.size() * kept.size());
    for (int k : kept) {
      const std::vector<float>& all = steps_[k].surface.*spec.values;
      for (std::size_t b : source) values.push_back(all[b]);
    }
    fields.push_back({{"key", spec.key}, {"label", spec.label}, {"unit", spec.unit}, {"scale", spec.scale},
                      {"values", quantized_array(values, 1)}});
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * shown.triangles.size());
  for (const auto& t : shown.triangles) indices.insert(indices.end(), t.begin(), t.end());

  nlohmann::json view = {{"format", "needlekit-view/1"}, {"kind", "indentation"}, {"name", case_.name}};
  view["title"] = fmt::format("{}: deformed tissue surface, {} of {} load steps", case_.name, kept.size(), total);
  nlohmann::json step_list = nlohmann::json::array();
  for (int k : kept) {
    const insertion::IndentationStep& s = steps_[k].step;
    step_list.push_back({{"label", fmt::format("step {}: depth {:.4g} um, force {:.4g} N", k + 1, s.depth * 1e6, s.force)},
                         {"depth_um", s.depth * 1e6},
                         {"force_N", s.force}});
  }
  view["steps"] = step_list;
  view["steps_total"] = total;
  view["surface"] = {{"region", whole ? "boundary" : "top"},
                     {"vertices", shown.nodes.size()},
                     {"triangles", shown.triangles.size()},
                     {"indices", uint32_array(indices)},
                     {"positions", quantized_array(positions, 3)},
                     {"fields", fields}};
  view["needles"] = needles_json(kept);
  nlohmann::json notes = nlohmann::json::array();
  if (!whole) {
    notes.push_back(fmt::format("only the top surface is shown ({} of the boundary's {} triangles): the whole boundary "
                                "would exceed {:.3g} MB",
                                shown.triangles.size(), boundary_.triangles.size(), options_.max_bytes * 1e-6));
  }
  if (static_cast<int>(kept.size()) < total) {
    notes.push_back(fmt::format("{} of {} load steps are shown (evenly spread, the last one kept) to stay within "
                                "{:.3g} MB",
                                kept.size(), total, options_.max_bytes * 1e-6));
  }
  view["notes"] = notes;
  return view;
}

nlohmann::json IndentationView::needles_json(const std::vector<int>& kept) const {
  // One mesh per distinct needle surface; the other needles are the same mesh translated (one needle mesh per case).
  const std::vector<fem::Indenter> indenters = insertion::placed_indenters(case_);
  nlohmann::json meshes = nlohmann::json::array(), instances = nlohmann::json::array();
  std::vector<const geometry::TriangleMesh*> distinct;
  for (const fem::Indenter& indenter : indenters) {
    const geometry::TriangleMesh& s = indenter.surface;
    int mesh = -1;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    for (std::size_t m = 0; m < distinct.size() && mesh < 0; ++m) {
      const geometry::TriangleMesh& d = *distinct[m];
      if (d.vertices.size() != s.vertices.size() || d.triangles != s.triangles || s.vertices.empty()) continue;
      const Eigen::Vector3d shift = s.vertices[0] - d.vertices[0];
      bool same = true;
      for (std::size_t v = 0; v < s.vertices.size() && same; ++v) {
        same = (s.vertices[v] - d.vertices[v] - shift).norm() <= 1e-9 * (1 + s.vertices[v].norm());
      }
      if (same) mesh = static_cast<int>(m), offset = shift;
    }
    if (mesh < 0) {
      mesh = static_cast<int>(distinct.size());
      distinct.push_back(&s);
      std::vector<float> positions;
      std::vector<std::uint32_t> indices;
      for (const Eigen::Vector3d& v : s.vertices) {
        for (float x : floats(v)) positions.push_back(x);
      }
      for (const auto& t : s.triangles) {
        for (int n : t) indices.push_back(static_cast<std::uint32_t>(n));
      }
      meshes.push_back({{"positions", float32_array(positions)}, {"indices", uint32_array(indices)}});
    }
    instances.push_back({{"mesh", mesh}, {"offset", floats(offset)}});
  }
  std::vector<double> displacement;
  for (int k : kept) displacement.push_back(steps_[k].indenter_displacement);
  // The per-needle table (an array's needles are coloured by a per-step column when there are several).
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t n = 0; n < case_.needles.size(); ++n) {
    nlohmann::json force = nlohmann::json::array();
    for (int k : kept) {
      const std::vector<double>& f = steps_[k].step.needle_force;
      force.push_back(n < f.size() ? f[n] : 0.0);
    }
    const insertion::NeedleSite& site = case_.needles[n];
    rows.push_back({n + 1, site.position.x() * 1e6, site.position.y() * 1e6, site.tip_height * 1e6, force});
    if (n < outcomes_.size()) append_outcome(rows.back(), outcomes_[n], kept);
  }
  nlohmann::json columns = nlohmann::json::array(
      {{{"key", "needle"}, {"label", "needle"}, {"unit", ""}},
       {{"key", "x_um"}, {"label", "x"}, {"unit", "um"}},
       {{"key", "y_um"}, {"label", "y"}, {"unit", "um"}},
       {{"key", "tip_height_um"}, {"label", "tip height"}, {"unit", "um"}},
       {{"key", "force_N"}, {"label", "force"}, {"unit", "N"}, {"per_step", true}, {"colour", true}}});
  if (!outcomes_.empty()) {
    for (nlohmann::json column : kOutcomeColumns) columns.push_back(std::move(column));
  }
  const Eigen::Vector3d direction =
      indenters.empty() ? Eigen::Vector3d(0, 0, -1) : indenters.front().direction.normalized();
  return {{"meshes", meshes},
          {"instances", instances},
          {"direction", floats(direction)},
          {"displacement_m", displacement},
          {"table", {{"columns", columns}, {"rows", rows}}}};
}

}  // namespace needlekit::io
