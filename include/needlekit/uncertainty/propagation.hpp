// Propagation of input uncertainty through a model by sampling: the distribution of each output (a probability
// with its 95 % interval for 0/1 indicators; mean, sd, quantiles and a histogram for continuous outputs) and its
// Sobol' indices (sobol_indices.hpp).
//
// Design: the N samples are split into G = min(16, N) groups (replicates): with method = sobol every group is an
// independently scrambled Sobol' sequence, with monte-carlo independent pseudo-random streams. Output statistics
// use the N rows of matrix A; the Sobol' indices also run B and the k matrices AB_i (N·(k + 2) runs). Intervals:
// Wilson for Monte Carlo probabilities, the normal approximation for Monte Carlo means, and the Student-t spread
// of the G replicates for quasi-Monte Carlo estimates (a probability's never narrower than ±G/N, the resolution of
// one replicate) and all Sobol' indices. Work is cut into blocks addressed by
// (group, block) and reduced in a fixed order, so the result is bit-for-bit the same on any number of threads.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "needlekit/uncertainty/confidence_interval.hpp"
#include "needlekit/uncertainty/input_transform.hpp"
#include "needlekit/uncertainty/sample_points.hpp"

namespace needlekit::uncertainty {

enum class OutputKind {
  Indicator,   // 0 or 1: an event; its mean is a probability
  Continuous,  // any real value
};

struct OutputSpec {
  std::string name;
  OutputKind kind = OutputKind::Continuous;
};

// A model y = f(x) of k inputs (SI values in the order of the InputTransform) and the declared outputs. An output
// may be NaN for a sample where it is not defined; it is then left out of that output's statistics and counted.
class Model {
public:
  virtual ~Model() = default;
  virtual const std::vector<OutputSpec>& outputs() const = 0;
  // Must be thread-safe (called concurrently).
  virtual void evaluate(const double* x, double* y) const = 0;
};

struct PropagationOptions {
  std::size_t samples = 4096;                    // N >= 2 (rows of A); sobol works best with N = 2^m
  SamplingMethod method = SamplingMethod::Sobol;
  std::uint64_t seed = 1;                        // any; the same seed gives the same numbers
  bool sobol_indices = true;                     // also run B and AB_i: N·(k + 2) evaluations instead of N
  int threads = 0;                               // >= 0; 0: all hardware threads
  int histogram_bins = 20;                       // >= 1, over [min, max] of each continuous output
  // Called with the fraction of sample blocks done in [0, 1] (never decreasing), from one thread at a time; return
  // false to stop: the blocks not yet started are skipped and propagate() throws needlekit::Interrupted.
  std::function<bool(double)> progress;
};

struct SobolIndex {
  double value = 0;  // NaN when undefined (the output does not vary)
  Interval ci95;
};

struct OutputSummary {
  std::string name;
  OutputKind kind = OutputKind::Continuous;
  std::size_t defined = 0;        // rows of A where the output is defined
  double mean = 0;                // the probability for an indicator
  Interval ci95;                  // of the mean
  double sd = 0;
  double q05 = 0, q50 = 0, q95 = 0;             // continuous outputs: quantiles (linear interpolation, type 7)
  std::vector<double> histogram_edges;         // continuous outputs: bins + 1 edges
  std::vector<std::size_t> histogram_counts;
  std::vector<SobolIndex> first, total;        // per input; empty without sobol_indices
};

struct PropagationResult {
  std::size_t samples = 0;
  std::size_t evaluations = 0;
  std::size_t groups = 0;
  std::vector<OutputSummary> outputs;  // in the model's order
  std::vector<std::vector<double>> samples_of_output;  // per continuous output: its values over A (NaN undefined)
};

// Throws InvalidInput for samples < 2, no inputs, histogram_bins < 1 or threads < 0.
PropagationResult propagate(const InputTransform& inputs, const Model& model, const PropagationOptions& options = {});

}  // namespace needlekit::uncertainty
