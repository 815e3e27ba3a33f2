#include "needlekit/uncertainty/fe_surrogate.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>

#include "needlekit/core/errors.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/uncertainty/fe_surrogate_parameters.hpp"
#include "windowed_input.hpp"

namespace needlekit::uncertainty {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The design's points stay inside the inputs' [0.5 %, 99.5 %] quantiles (beyond them the surface extrapolates).
constexpr double kDesignMargin = 0.005;
// Point-set groups of the design and validation runs (apart from the sampling's groups 0..15).
constexpr std::uint64_t kDesignGroup = 1u << 20, kValidationGroup = (1u << 20) + 1;

std::vector<mesh::TissueLayer> layers_of(const insertion::IndentationCase& c) {
  if (c.tissue_mesh) return c.tissue_mesh->layers;
  return c.block.layers.empty() ? materials::skin_layers() : c.block.layers;
}

double nominal_of(const FeInput& input, const insertion::IndentationCase& c) {
  return input.kind == FeInput::Kind::CriticalPressure ? *c.puncture.critical_pressure
                                                       : layers_of(c)[input.layer].youngs_modulus;
}

// `c` has its tissue mesh.
void set_input(const FeInput& input, double x, insertion::IndentationCase& c) {
  if (input.kind == FeInput::Kind::CriticalPressure) {
    c.puncture.critical_pressure = x;
  } else {
    c.tissue_mesh->layers[input.layer].youngs_modulus = x;
  }
}

FeRun fe_run(const insertion::IndentationCase& base, const std::vector<FeInput>& inputs, std::vector<double> x,
             const insertion::IndentationOptions& options = {}) {
  insertion::IndentationCase c = base;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (c.tissue_mesh) set_input(inputs[i], x[i], c);
  }
  const auto start = std::chrono::steady_clock::now();
  const insertion::IndentationResult r = insertion::run_indentation(c, options);
  FeRun run;
  run.inputs = std::move(x);
  run.status = r.status;
  if (r.puncture) {
    run.depth = r.puncture->depth;
    run.force = r.puncture->force;
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

// Scrambled Sobol' points of one group mapped into the inputs' [margin, 1 − margin] quantile range.
std::vector<std::vector<double>> design_points(const InputTransform& transform, std::uint64_t seed, std::uint64_t group,
                                               int rows) {
  const std::size_t k = transform.size();
  std::vector<double> u(static_cast<std::size_t>(rows) * k);
  uniform_points(SamplingMethod::Sobol, seed, group, k, 0, static_cast<std::size_t>(rows), u.data());
  std::vector<std::vector<double>> points;
  for (int r = 0; r < rows; ++r) {
    std::vector<double> v(k), x(k);
    for (std::size_t i = 0; i < k; ++i) v[i] = kDesignMargin + (1 - 2 * kDesignMargin) * u[r * k + i];
    transform.values(v.data(), x.data());
    points.push_back(std::move(x));
  }
  return points;
}

RelativeError relative_error(const std::vector<FeRun>& runs, bool depth) {
  RelativeError e;
  int count = 0;
  for (const FeRun& run : runs) {
    if (!run.depth) continue;
    const double y = depth ? *run.depth : *run.force;
    const double error = std::abs((depth ? run.surrogate_depth : run.surrogate_force) - y) / std::abs(y);
    e.max = std::max(e.max, error);
    e.rms += error * error;
    ++count;
  }
  e.rms = count > 0 ? std::sqrt(e.rms / count) : 0.0;
  return e;
}

class SurrogateModel : public Model {
public:
  SurrogateModel(std::function<void(const double*, double&, double&)> surrogate, double limit)
      : surrogate_(std::move(surrogate)), limit_(limit) {}
  const std::vector<OutputSpec>& outputs() const override { return outputs_; }
  void evaluate(const double* x, double* y) const override {
    surrogate_(x, y[0], y[1]);
    y[2] = y[0] <= limit_;
  }

private:
  std::function<void(const double*, double&, double&)> surrogate_;
  double limit_;
  std::vector<OutputSpec> outputs_{{"puncture_depth", OutputKind::Continuous},
                                   {"puncture_force", OutputKind::Continuous},
                                   {"punctures_before_depth", OutputKind::Indicator}};
};

// The log-quadratic response surfaces of the puncture depth and force in the active inputs, fitted to FE runs at
// design points and checked against held-out runs (result.design, .validation and their errors); empty, with
// result.status Failed, when too few design runs punctured to fit the terms.
std::function<void(const double*, double&, double&)> fitted_surrogate(
    const insertion::IndentationCase& c, const std::vector<FeInput>& which, const std::vector<double>& nominal,
    const std::vector<std::size_t>& active, const InputTransform& transform, const FeSurrogateOptions& options,
    FeSurrogateResult& result) {
  const int a = static_cast<int>(active.size());
  result.terms = LogQuadraticSurface::terms(a);
  const int design_runs = options.design_runs > 0 ? options.design_runs : 2 * result.terms;
  const std::uint64_t seed = options.sampling.seed;
  const auto points = design_points(transform, seed, kDesignGroup, design_runs);
  const auto held_out = design_points(transform, seed, kValidationGroup, options.validation_runs);
  const int total = design_runs + options.validation_runs;
  int done = 0;
  for (const auto& x : points) {
    result.design.push_back(fe_run(c, which, x));
    if (options.progress) options.progress(++done, total);
  }
  const auto active_inputs = [&](const std::vector<double>& x) {
    std::vector<double> v;
    for (std::size_t i : active) v.push_back(x[i]);
    return v;
  };
  std::vector<std::vector<double>> fit_inputs;
  std::vector<double> depths, forces;
  for (const FeRun& run : result.design) {
    if (!run.depth) continue;
    fit_inputs.push_back(active_inputs(run.inputs));
    depths.push_back(*run.depth);
    forces.push_back(*run.force);
  }
  const int censored = design_runs - static_cast<int>(depths.size());
  if (static_cast<int>(depths.size()) < result.terms) {
    result.status = FeSurrogateStatus::Failed;
    result.reason = fmt::format("{} of {} design runs did not puncture within the loading depth {:.4g} um, leaving "
                                "{} for {} terms: deepen [loading] depth or narrow the spreads",
                                censored, design_runs, c.depth * 1e6, depths.size(), result.terms);
    return {};
  }
  std::vector<double> active_nominal = active_inputs(nominal);
  const auto depth_surface = std::make_shared<LogQuadraticSurface>(active_nominal, fit_inputs, depths);
  const auto force_surface = std::make_shared<LogQuadraticSurface>(active_nominal, fit_inputs, forces);
  const std::function<void(const double*, double&, double&)> surrogate =
      [depth_surface, force_surface, active](const double* x, double& d, double& f) {
        std::vector<double> v;
        for (std::size_t i : active) v.push_back(x[i]);
        d = (*depth_surface)(v.data());
        f = (*force_surface)(v.data());
      };
  for (const auto& x : held_out) {
    result.validation.push_back(fe_run(c, which, x));
    if (options.progress) options.progress(++done, total);
  }
  int censored_validation = 0;
  for (auto* runs : {&result.design, &result.validation}) {
    for (FeRun& run : *runs) {
      surrogate(run.inputs.data(), run.surrogate_depth, run.surrogate_force);
      censored_validation += runs == &result.validation && !run.depth;
    }
  }
  result.design_depth_error = relative_error(result.design, true);
  result.design_force_error = relative_error(result.design, false);
  result.validation_depth_error = relative_error(result.validation, true);
  result.validation_force_error = relative_error(result.validation, false);
  if (censored + censored_validation > 0) {
    result.status = FeSurrogateStatus::CensoredRuns;
    result.reason = fmt::format("{} design and {} validation runs did not puncture within the loading depth "
                                "{:.4g} um: left out of the fit and of the stated error",
                                censored, censored_validation, c.depth * 1e6);
  }
  if (censored_validation == options.validation_runs) {
    result.notes.push_back("no held-out run punctured: the surrogate's error is not checked");
  }
  return surrogate;
}

}  // namespace

std::string_view to_string(FeSurrogateStatus status) { return name_of(kFeSurrogateStatusNames, status); }

FeInput fe_input_from_key(std::string_view key, const insertion::IndentationCase& c, std::string_view what) {
  if (key == "puncture.critical_pressure") {
    if (!c.puncture.critical_pressure) {
      throw InvalidInput(fmt::format("{}: the case has no [puncture] critical_pressure, expected an input the case has",
                                     what));
    }
    return {FeInput::Kind::CriticalPressure, 0};
  }
  constexpr std::string_view prefix = "tissue.layers.", suffix = ".youngs_modulus";
  if (key.size() > prefix.size() + suffix.size() && key.substr(0, prefix.size()) == prefix &&
      key.substr(key.size() - suffix.size()) == suffix) {
    const std::string_view index = key.substr(prefix.size(), key.size() - prefix.size() - suffix.size());
    const bool digits = !index.empty() && index.size() < 4 &&
                        index.find_first_not_of("0123456789") == std::string_view::npos;
    const int layers = static_cast<int>(layers_of(c).size());
    if (digits && std::stoi(std::string(index)) < layers) return {FeInput::Kind::LayerModulus, std::stoi(std::string(index))};
    if (digits) {
      throw InvalidInput(fmt::format("{}: layer {} does not exist, expected a layer index in [0, {}]", what, index,
                                     layers - 1));
    }
  }
  throw InvalidInput(fmt::format("{}: '{}' is not an input of an FE case, expected one of: {}", what, key,
                                 kFeInputKeys));
}

InputTransform fe_input_transform(const insertion::IndentationCase& c, const std::vector<DesignUncertainInput>& inputs,
                                  const std::vector<Correlation>& correlations, std::vector<std::string>& notes) {
  std::vector<UncertainInput> resolved;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string what = fmt::format("uncertain.\"{}\"", inputs[i].key);
    const FeInput input = fe_input_from_key(inputs[i].key, c, what);
    for (std::size_t j = 0; j < i; ++j) {
      if (inputs[j].key == inputs[i].key) throw InvalidInput(fmt::format("{}: given twice, expected each input once", what));
    }
    const detail::InputRange range{units::Dimension::Pressure, "MPa", 0, kInf,
                           input.kind == FeInput::Kind::CriticalPressure ? "P_c of the critical-pressure criterion (Eq 3.17)"
                                                                         : "E of the layer"};
    resolved.push_back(detail::windowed_input(inputs[i], nominal_of(input, c), range, what, notes));
  }
  return detail::noted_transform(std::move(resolved), correlations, notes);
}

FeSurrogateResult fe_surrogate(const insertion::IndentationCase& base, const std::vector<DesignUncertainInput>& inputs,
                               const std::vector<Correlation>& correlations, const FeSurrogateOptions& options) {
  insertion::validate(base);
  if (base.block.split && !base.tissue_mesh) {
    throw InvalidInput("mesh.split: the FE surrogate reuses one tissue mesh and has no two-grid level, expected "
                       "split = false");
  }
  check_ranges(kFeSurrogateParameters, options, "surrogate");
  FeSurrogateResult result;
  result.depth_limit = options.depth_limit ? *options.depth_limit : base.depth;
  if (!(result.depth_limit > 0)) throw InvalidInput("surrogate.depth_limit: expected a depth > 0");
  const InputTransform transform = fe_input_transform(base, inputs, correlations, result.notes);
  std::vector<FeInput> which;
  for (const DesignUncertainInput& input : inputs) {
    result.keys.push_back(input.key);
    which.push_back(fe_input_from_key(input.key, base, input.key));
  }
  const std::size_t k = inputs.size();
  std::vector<double> nominal(k);
  std::vector<std::size_t> active;  // inputs with a spread
  for (std::size_t i = 0; i < k; ++i) {
    nominal[i] = nominal_of(which[i], base);
    if (transform.value(i, 0.05) != transform.value(i, 0.95)) active.push_back(i);
  }

  // The nominal run meshes the block; every other run reuses its mesh.
  insertion::IndentationCase c = base;
  insertion::IndentationOptions capture;
  capture.on_mesh = [&c](const mesh::TetMesh& tissue) { c.tissue_mesh = tissue; };
  result.nominal = fe_run(base, which, nominal, capture);
  result.elements = c.tissue_mesh ? static_cast<int>(c.tissue_mesh->tets.size()) : 0;
  if (!result.nominal.depth) {
    result.status = FeSurrogateStatus::Failed;
    result.reason = fmt::format("the nominal FE run did not puncture within the loading depth {:.4g} um ({}): "
                                "deepen [loading] depth",
                                base.depth * 1e6, insertion::to_string(result.nominal.status));
    return result;
  }

  std::function<void(const double*, double&, double&)> surrogate;
  if (active.empty()) {  // no spread: the surrogate is the nominal run itself
    const double depth = *result.nominal.depth, force = *result.nominal.force;
    surrogate = [depth, force](const double*, double& d, double& f) { d = depth, f = force; };
  } else {
    surrogate = fitted_surrogate(c, which, nominal, active, transform, options, result);
    if (!surrogate) return result;
  }
  if (result.depth_limit > base.depth) {
    result.notes.push_back(fmt::format("depth_limit {:.4g} um is beyond the FE runs' loading depth {:.4g} um: the "
                                       "surrogate extrapolates there",
                                       result.depth_limit * 1e6, base.depth * 1e6));
  }
  result.surrogate = surrogate;
  const SurrogateModel model(surrogate, result.depth_limit);
  result.propagation = propagate(transform, model, options.sampling);
  return result;
}

}  // namespace needlekit::uncertainty
