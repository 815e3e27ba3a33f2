// FE puncture under uncertainty, cheaply and honestly (issue 15): the FE indentation of a case
// (insertion::run_indentation, §3.4–3.5) is too slow to sample directly, so
//   1. the tissue mesh is built once (the nominal run's) and a small space-filling design of FE runs is made on it
//      (scrambled Sobol' points in the inputs' probability space, u in [0.005, 0.995], mapped by the inputs'
//      quantiles), each run with the layer moduli and the critical pressure of its point;
//   2. the puncture depth and force are fitted by a quadratic response surface in the log inputs
//      (response_surface.hpp);
//   3. the surface is checked on held-out FE runs at other points: the result states its maximum and rms relative
//      error there (and at the design runs);
//   4. the surrogate is sampled by propagate() for P(puncture before depth X) and the distributions of the puncture
//      depth and force.
// Inputs (fe_inputs()): tissue.layers.N.youngs_modulus (N from 0, top layer first) and puncture.critical_pressure.
// Inputs without spread are left out of the polynomial; with none left the surrogate is the nominal FE run itself.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"
#include "needlekit/uncertainty/response_surface.hpp"

namespace needlekit::uncertainty {

// An uncertain input of an FE case: a layer's Young's modulus or the critical pressure (Pa, > 0).
struct FeInput {
  enum class Kind { LayerModulus, CriticalPressure } kind = Kind::LayerModulus;
  int layer = 0;  // LayerModulus: index from the top
};
// The input of a key ("tissue.layers.1.youngs_modulus", "puncture.critical_pressure"); throws InvalidInput naming
// `what` for another key, a layer the case does not have, or a critical pressure the case does not use.
FeInput fe_input_from_key(std::string_view key, const insertion::IndentationCase& c, std::string_view what);
// The keys' forms, for messages and help.
inline constexpr std::string_view kFeInputKeys = "tissue.layers.N.youngs_modulus (N = 0 for the top layer), "
                                                 "puncture.critical_pressure";

// Resolves keys and physical ranges (> 0) as design_input_transform() does; needs no FE run.
InputTransform fe_input_transform(const insertion::IndentationCase& c, const std::vector<DesignUncertainInput>& inputs,
                                  const std::vector<Correlation>& correlations, std::vector<std::string>& notes);

struct FeSurrogateOptions {
  PropagationOptions sampling;
  int design_runs = 0;                // FE runs of the fit, >= the polynomial's terms; 0: 2 × the terms
  int validation_runs = 4;            // held-out FE runs, >= 1
  std::optional<double> depth_limit;  // m, > 0: X of P(puncture before X); default: the case's loading depth
  std::function<void(int done, int total)> progress;  // after each FE run (may be empty)
};

struct FeRun {
  std::vector<double> inputs;          // SI, in the order of the inputs
  insertion::IndentationStatus status = insertion::IndentationStatus::ReachedDepth;
  std::optional<double> depth, force;  // m, N: the puncture point (empty: no puncture within the loading depth)
  double surrogate_depth = 0, surrogate_force = 0;  // m, N: the fitted surface at this run's inputs
  double seconds = 0;                  // wall time of the FE run
};

struct RelativeError {
  double max = 0, rms = 0;  // |ŷ − y| / y over the runs
};

enum class FeSurrogateStatus {
  Ok,
  CensoredRuns,  // some FE runs did not puncture within the loading depth: left out of the fit (reason: how many)
  Failed,        // too few punctured runs to fit (nothing was sampled; reason says why)
};
inline constexpr EnumTable<FeSurrogateStatus, 3> kFeSurrogateStatusNames{{
    {FeSurrogateStatus::Ok, "ok", "every FE run punctured within the loading depth"},
    {FeSurrogateStatus::CensoredRuns, "censored_runs",
     "some FE runs did not puncture within the loading depth: left out of the fit"},
    {FeSurrogateStatus::Failed, "failed", "too few punctured runs to fit; nothing was sampled"},
}};
std::string_view to_string(FeSurrogateStatus status);

struct FeSurrogateResult {
  FeSurrogateStatus status = FeSurrogateStatus::Ok;
  std::string reason;
  std::vector<std::string> keys;
  FeRun nominal;                      // the FE run at the nominal inputs (its mesh is reused by every run)
  int elements = 0;                   // of the tissue mesh
  int terms = 1;                      // of each polynomial
  std::vector<FeRun> design, validation;
  RelativeError design_depth_error, design_force_error;          // at the design runs (the fit's residuals)
  RelativeError validation_depth_error, validation_force_error;  // at the held-out runs: the stated error
  double depth_limit = 0;             // m
  PropagationResult propagation;      // outputs: puncture_depth (m), puncture_force (N), punctures_before_depth
  std::vector<std::string> notes;
  std::function<void(const double* x, double& depth, double& force)> surrogate;  // the fitted model (SI)

  const OutputSummary& depth() const { return propagation.outputs[0]; }
  const OutputSummary& force() const { return propagation.outputs[1]; }
  const OutputSummary& punctures_before() const { return propagation.outputs[2]; }
};

// Throws InvalidInput for an invalid case, inputs or options; FE failures are statuses.
FeSurrogateResult fe_surrogate(const insertion::IndentationCase& c, const std::vector<DesignUncertainInput>& inputs,
                               const std::vector<Correlation>& correlations, const FeSurrogateOptions& options = {});

}  // namespace needlekit::uncertainty
