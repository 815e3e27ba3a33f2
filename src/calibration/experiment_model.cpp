#include "needlekit/calibration/experiment_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <fmt/format.h>

#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/calibration/case_parameters.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/insertion_curve.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/indentation_output.hpp"
#include "needlekit/io/insertion_case.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"

namespace needlekit::calibration {

struct ExperimentModel::Setup {
  std::optional<mesh::TetMesh> tissue;                // the block meshed once (indent/insert cases meshed here)
  std::optional<insertion::PostPunctureLoads> loads;  // insert cases
};

namespace {

std::filesystem::path base_of(const ExperimentSpec& e) {
  return e.case_path.has_parent_path() ? e.case_path.parent_path() : std::filesystem::path(".");
}

// The indentation case of an indent or insert case text, with the pre-meshed tissue.
insertion::IndentationCase fe_case(const ExperimentSpec& e, const std::string& text,
                                   const std::optional<mesh::TetMesh>& tissue, io::InsertionSettings* settings) {
  const std::filesystem::path base = base_of(e);
  std::string indentation_text = text;
  if (settings) {
    *settings = io::parse_insertion_settings(text, e.case_path.string(), base);
    indentation_text = settings->indentation_text;
  }
  insertion::IndentationCase c = io::parse_indentation_case_toml(indentation_text, e.case_path.string(), base);
  if (tissue && !c.tissue_mesh) {
    c.tissue_mesh = *tissue;
    c.tissue_mesh->layers = c.block.layers;  // the fitted moduli; the geometry does not change
  }
  return c;
}

// A curve sample's residual is relative to its own force, floored at this fraction of the largest measured force so
// that samples near zero (first contact) do not dominate.
constexpr double kForceFloor = 0.05;

double largest_magnitude(const std::vector<double>& values) {
  double largest = 0;
  for (double v : values) largest = std::max(largest, std::abs(v));
  return largest;
}

}  // namespace

double force_at(const insertion::ForceDepthCurve& curve, double depth) {
  const auto& x = curve.depth;
  const auto& y = curve.force;
  if (x.empty()) return 0;
  if (depth <= x.front()) return y.front();
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (x[i] >= depth && x[i] > x[i - 1]) return y[i - 1] + (y[i] - y[i - 1]) * (depth - x[i - 1]) / (x[i] - x[i - 1]);
  }
  return y.back();
}

ExperimentModel::ExperimentModel(const ExperimentSpec& experiment, const std::vector<ParameterSpec>& parameters,
                                 double mesh_scale)
    : experiment_(experiment), parameters_(parameters), setup_(std::make_unique<Setup>()) {
  if (!(mesh_scale > 0 && mesh_scale <= 1)) {
    throw std::invalid_argument(fmt::format("ExperimentModel: mesh_scale {} outside (0, 1]", mesh_scale));
  }
  for (const ParameterSpec& p : parameters_)
    uses_.push_back(case_value(experiment_.case_text, p.path, experiment_.case_path.string()).has_value());
  if (experiment_.measured && experiment_.curve_weight > 0) {
    residual_count_ += experiment_.measured->depth.size();
    force_scale_ = largest_magnitude(experiment_.measured->force);
    if (!(force_scale_ > 0)) {
      throw InvalidInput(fmt::format("{}: {}: every measured force is zero, expected a curve with forces",
                                     experiment_.where, experiment_.measured_path->string()));
    }
  }
  if (experiment_.puncture_weight > 0) residual_count_ += experiment_.puncture.depth.has_value() + experiment_.puncture.force.has_value();

  std::vector<double> initial;
  for (const ParameterSpec& p : parameters_) initial.push_back(p.initial);
  const std::string text = case_text(initial);
  if (experiment_.kind == ExperimentKind::Design) {
    io::parse_design_toml(text, experiment_.case_path.string());  // reads, or throws naming the case file's key
    return;
  }
  io::InsertionSettings settings;
  const bool insertion = experiment_.kind == ExperimentKind::Insertion;
  insertion::IndentationCase c = fe_case(experiment_, text, std::nullopt, insertion ? &settings : nullptr);
  insertion::validate(c);
  const double reach = insertion ? settings.curve.final_depth : c.depth;
  if (experiment_.measured && experiment_.measured->depth.back() > reach * (1 + 1e-9)) {
    throw InvalidInput(fmt::format("{}: {}: the measured curve goes to {:.6g} um, deeper than the case's {} of "
                                   "{:.6g} um, expected {} >= the deepest measured sample",
                                   experiment_.where, experiment_.measured_path->string(),
                                   experiment_.measured->depth.back() * 1e6,
                                   insertion ? "post_puncture.final_depth" : "loading.depth", reach * 1e6,
                                   insertion ? "final_depth" : "depth"));
  }
  if (!c.tissue_mesh && !settings.pre_puncture) {
    mesh::LayeredBlockOptions block = c.block;
    block.insertion_sites.clear();
    for (const insertion::NeedleSite& site : c.needles) block.insertion_sites.push_back(site.position);
    block.split = false;  // the two-grid coarse level is not kept with a reused mesh
    block.size_at_site *= mesh_scale;
    block.size_far *= mesh_scale;
    setup_->tissue = mesh::layered_block_mesh(block).mesh;
  }
  if (insertion) {
    insertion::TriangleClassificationOptions classification = settings.classification;
    if (c.geometry) classification.bore_radius = 0.5 * c.geometry->bore_diameter;
    setup_->loads = insertion::post_puncture_loads(c.needle, classification, settings.post_puncture);
  }
}

ExperimentModel::~ExperimentModel() = default;
bool ExperimentModel::meshes_block() const { return setup_->tissue.has_value(); }
ExperimentModel::ExperimentModel(ExperimentModel&&) noexcept = default;

std::string ExperimentModel::case_text(const std::vector<double>& values, bool user_units, int digits) const {
  std::string text = experiment_.case_text;
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    if (!uses_.empty() && !uses_[i]) continue;
    if (!case_value(text, parameters_[i].path, experiment_.case_path.string())) continue;
    text = with_case_value(text, parameters_[i].path, values[i], parameters_[i].dimension,
                           user_units ? std::string_view(parameters_[i].unit) : std::string_view(), digits);
  }
  return text;
}

Prediction ExperimentModel::predict(const std::vector<double>& values,
                                    const std::vector<insertion::StepDisplacement>* warm_start,
                                    bool keep_displacements, const std::function<bool()>& stop_requested) const {
  Prediction prediction;
  const std::string text = case_text(values);
  if (experiment_.kind == ExperimentKind::Design) {
    const io::DesignFile file = io::parse_design_toml(text, experiment_.case_path.string());
    const analysis::PerformanceIndexResult r = analysis::performance_index(file.design, file.conditions, file.options);
    prediction.ok = true;
    prediction.puncture = insertion::PuncturePoint{r.deformation, r.puncture_force, insertion::PunctureCriterion::None};
    prediction.status = fmt::format("F(A) = {:.6g} N ({}), d = {:.6g} um{}", r.puncture_force,
                                    analysis::to_string(r.puncture_force_law), r.deformation * 1e6,
                                    r.small_tip_branch ? " (small-tip line)" : " (Eq 4.3)");
    prediction.notes = r.notes;
    return prediction;
  }
  const bool insertion = experiment_.kind == ExperimentKind::Insertion;
  io::InsertionSettings settings;
  insertion::IndentationCase c = fe_case(experiment_, text, setup_->tissue, insertion ? &settings : nullptr);
  // An indent experiment's curve goes on past the puncture point (to every measured depth); without a curve the run
  // stops at the puncture, as an insert case's does.
  c.stop_at_puncture = insertion || !(experiment_.measured && experiment_.curve_weight > 0);
  if (insertion && settings.pre_puncture) {  // [pre_puncture] curve given: no FE
    prediction.status = "pre-puncture curve from the case's [pre_puncture] table";
    return cutting(prediction, settings, *settings.pre_puncture, std::nullopt);
  }
  insertion::IndentationOptions fe_options;
  fe_options.warm_start = warm_start;
  fe_options.keep_displacements = keep_displacements;
  struct StopRequested {};  // thrown from the FE's progress (every Newton iteration), caught right here
  if (stop_requested) {
    fe_options.progress = [&stop_requested](const insertion::IndentationProgress&) {
      if (stop_requested()) throw StopRequested{};
    };
  }
  insertion::IndentationResult fe;
  try {
    fe = insertion::run_indentation(c, fe_options);
  } catch (const StopRequested&) {
    prediction.stopped = true;
    prediction.failure = fmt::format("{}: stopped on request", experiment_.name);
    return prediction;
  }
  prediction.model_runs = 1;
  prediction.warm_started_steps = fe.warm_started_steps;
  if (keep_displacements) {
    prediction.displacements =
        std::make_shared<const std::vector<insertion::StepDisplacement>>(std::move(fe.displacements));
  }
  prediction.elements = fe.elements;
  prediction.status = fmt::format("FE ({}): {}: {}", io::fe_models_text(c), insertion::to_string(fe.status),
                                  fe.reason);
  prediction.reason = fe.reason;
  if (fe.steps.empty()) {
    prediction.failure = fmt::format("{}: the FE converged no load step ({})", experiment_.name, fe.reason);
    return prediction;
  }
  if (!insertion) {
    prediction.curve = insertion::pre_puncture_curve(fe).curve;
    prediction.puncture = fe.puncture;
    prediction.ok = fe.status != insertion::IndentationStatus::SolverFailed ||
                    fe.steps.back().depth >= (experiment_.measured ? experiment_.measured->depth.back() : 0);
    if (!prediction.ok) prediction.failure = fmt::format("{}: {}", experiment_.name, fe.reason);
    return prediction;
  }
  return cutting(prediction, settings, insertion::pre_puncture_curve(fe), fe.puncture);
}

Prediction ExperimentModel::cutting(Prediction prediction, const io::InsertionSettings& settings,
                                    const insertion::PrePunctureCurve& pre,
                                    const std::optional<insertion::PuncturePoint>& fe_puncture) const {
  insertion::NeedleInsertion needle;
  needle.pre_puncture = pre;
  needle.loads = &*setup_->loads;
  needle.stiffness = settings.model.stiffness;
  needle.scale = settings.model.scale;
  const insertion::InsertionCurve curve = insertion::insertion_curve({needle}, settings.curve);
  prediction.curve.depth = curve.depth;
  prediction.curve.force = curve.force;
  if (!curve.punctures.empty()) {
    prediction.puncture = insertion::PuncturePoint{curve.punctures.front().displacement,
                                                   curve.punctures.front().force_before,
                                                   fe_puncture ? fe_puncture->criterion : insertion::PunctureCriterion::None};
  }
  prediction.ok = true;
  return prediction;
}

std::vector<double> ExperimentModel::residuals(const Prediction& p) const {
  std::vector<double> r;
  r.reserve(residual_count_);
  if (experiment_.measured && experiment_.curve_weight > 0) {
    const auto& m = *experiment_.measured;
    for (std::size_t i = 0; i < m.depth.size(); ++i) {
      const double scale = std::max(std::abs(m.force[i]), kForceFloor * force_scale_);
      r.push_back(experiment_.curve_weight * (force_at(p.curve, m.depth[i]) - m.force[i]) / scale);
    }
  }
  if (experiment_.puncture_weight > 0) {
    // Without a model puncture the end of the model's curve stands in (a large, finite residual).
    const double depth = p.puncture ? p.puncture->depth : (p.curve.depth.empty() ? 0.0 : p.curve.depth.back());
    const double force = p.puncture ? p.puncture->force : (p.curve.force.empty() ? 0.0 : p.curve.force.back());
    if (experiment_.puncture.depth)
      r.push_back(experiment_.puncture_weight * (depth - *experiment_.puncture.depth) / *experiment_.puncture.depth);
    if (experiment_.puncture.force)
      r.push_back(experiment_.puncture_weight * (force - *experiment_.puncture.force) / *experiment_.puncture.force);
  }
  return r;
}

}  // namespace needlekit::calibration
