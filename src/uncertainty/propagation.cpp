#include "needlekit/uncertainty/propagation.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fmt/format.h>
#include <mutex>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/uncertainty/propagation_parameters.hpp"
#include "needlekit/uncertainty/sobol_indices.hpp"

namespace needlekit::uncertainty {
namespace {

constexpr std::size_t kMaxGroups = 16;

// Sums of one output over the A rows of a block.
struct MomentSums {
  std::size_t rows = 0;
  double sum = 0, sum2 = 0;
  void add(double y) {
    ++rows;
    sum += y;
    sum2 += y * y;
  }
  void add(const MomentSums& other) {
    rows += other.rows;
    sum += other.sum;
    sum2 += other.sum2;
  }
};

// One block of rows of one group.
struct Task {
  std::size_t group = 0;
  std::size_t block = 0;
  std::size_t rows = 0;
  std::size_t first_row = 0;  // global index of the block's first row in the A matrix
};

struct TaskSums {
  std::vector<MomentSums> moments;  // per output
  std::vector<SobolSums> sobol;     // per output × input
};

class Sampler {
public:
  Sampler(const InputTransform& inputs, const Model& model, const PropagationOptions& options)
      : inputs_(inputs), model_(model), options_(options), k_(inputs.size()), outputs_(model.outputs().size()) {
    // Shift: the outputs at the inputs' medians (u = 1/2), to keep the sums well conditioned.
    std::vector<double> u(k_, 0.5), x(k_);
    shift_.assign(outputs_, 0.0);
    inputs_.values(u.data(), x.data());
    model_.evaluate(x.data(), shift_.data());
    for (double& c : shift_) c = std::isfinite(c) ? c : 0.0;
  }

  std::size_t dimension() const { return options_.sobol_indices ? 2 * k_ : k_; }

  void run(const Task& task, TaskSums& sums, std::vector<std::vector<double>>& stored,
           const std::vector<std::size_t>& stored_output) const {
    const std::size_t d = dimension();
    std::vector<double> u(task.rows * d);
    uniform_points(options_.method, options_.seed, task.group, d, task.block, task.rows, u.data());
    sums.moments.assign(outputs_, {});
    sums.sobol.assign(options_.sobol_indices ? outputs_ * k_ : 0, {});
    std::vector<double> xa(k_), xb(k_), xab(k_), uab(k_), ya(outputs_), yb(outputs_), yab(outputs_);
    for (std::size_t r = 0; r < task.rows; ++r) {
      const double* ua = &u[r * d];
      inputs_.values(ua, xa.data());
      model_.evaluate(xa.data(), ya.data());
      for (std::size_t o = 0; o < outputs_; ++o) {
        if (std::isfinite(ya[o])) sums.moments[o].add(ya[o] - shift_[o]);
      }
      for (std::size_t s = 0; s < stored_output.size(); ++s) stored[s][task.first_row + r] = ya[stored_output[s]];
      if (!options_.sobol_indices) continue;
      const double* ub = ua + k_;
      inputs_.values(ub, xb.data());
      model_.evaluate(xb.data(), yb.data());
      for (std::size_t i = 0; i < k_; ++i) {
        if (inputs_.correlated()) {  // AB_i is taken in the independent uniforms, then correlated
          std::copy(ua, ua + k_, uab.begin());
          uab[i] = ub[i];
          inputs_.values(uab.data(), xab.data());
        } else {
          xab = xa;
          xab[i] = xb[i];
        }
        model_.evaluate(xab.data(), yab.data());
        for (std::size_t o = 0; o < outputs_; ++o) {
          if (std::isfinite(ya[o]) && std::isfinite(yb[o]) && std::isfinite(yab[o])) {
            sums.sobol[o * k_ + i].add(ya[o] - shift_[o], yb[o] - shift_[o], yab[o] - shift_[o]);
          }
        }
      }
    }
  }

  double shift(std::size_t o) const { return shift_[o]; }

private:
  const InputTransform& inputs_;
  const Model& model_;
  const PropagationOptions& options_;
  std::size_t k_, outputs_;
  std::vector<double> shift_;
};

void validate(const InputTransform& inputs, const Model& model, const PropagationOptions& options) {
  check_ranges(kPropagationParameters, options, "sampling");
  if (inputs.size() == 0) throw InvalidInput("uncertain: no uncertain inputs, expected at least one");
  if (model.outputs().empty()) throw InvalidInput("model: no outputs");
}

// Type-7 quantile (linear interpolation between order statistics) of sorted values.
double sorted_quantile(const std::vector<double>& sorted, double level) {
  const double h = (static_cast<double>(sorted.size()) - 1) * level;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

void describe_distribution(const std::vector<double>& values, int bins, OutputSummary& summary) {
  std::vector<double> sorted;
  sorted.reserve(values.size());
  for (double v : values) {
    if (std::isfinite(v)) sorted.push_back(v);
  }
  if (sorted.empty()) return;
  std::sort(sorted.begin(), sorted.end());
  summary.q05 = sorted_quantile(sorted, 0.05);
  summary.q50 = sorted_quantile(sorted, 0.50);
  summary.q95 = sorted_quantile(sorted, 0.95);
  const double lo = sorted.front(), hi = sorted.back();
  const int count = hi > lo ? bins : 1;
  summary.histogram_edges.resize(static_cast<std::size_t>(count) + 1);
  for (int b = 0; b <= count; ++b) summary.histogram_edges[static_cast<std::size_t>(b)] = lo + (hi - lo) * b / count;
  summary.histogram_counts.assign(static_cast<std::size_t>(count), 0);
  for (double v : sorted) {
    const double position = hi > lo ? (v - lo) / (hi - lo) * count : 0.0;
    ++summary.histogram_counts[std::min(static_cast<std::size_t>(position), static_cast<std::size_t>(count - 1))];
  }
}

// Groups of n/G rows (the first n % G groups one more), each cut into blocks.
std::vector<Task> sample_tasks(std::size_t n, std::size_t groups) {
  std::vector<Task> tasks;
  std::size_t row = 0;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t rows = n / groups + (g < n % groups ? 1 : 0);
    for (std::size_t b = 0; b * kSampleBlockRows < rows; ++b) {
      const std::size_t block_rows = std::min(kSampleBlockRows, rows - b * kSampleBlockRows);
      tasks.push_back({g, b, block_rows, row});
      row += block_rows;
    }
  }
  return tasks;
}

TaskSums empty_sums(std::size_t outputs, std::size_t sobol_terms) {
  TaskSums sums;
  sums.moments.assign(outputs, {});
  sums.sobol.assign(sobol_terms, {});
  return sums;
}

void add_sums(TaskSums& to, const TaskSums& from) {
  for (std::size_t o = 0; o < to.moments.size(); ++o) to.moments[o].add(from.moments[o]);
  for (std::size_t s = 0; s < to.sobol.size(); ++s) to.sobol[s].add(from.sobol[s]);
}

// Mean, standard deviation and the 95 % interval of output o: Wilson's for an indicator under Monte Carlo (or when
// every or no sample succeeded), the normal one for Monte Carlo, else from the replicates (the groups' means).
void describe_moments(const Sampler& sampler, std::size_t o, const OutputSpec& spec, const TaskSums& total,
                      const std::vector<TaskSums>& per_group, const PropagationOptions& options,
                      OutputSummary& summary) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const MomentSums& m = total.moments[o];
  summary.defined = m.rows;
  if (m.rows == 0) {
    summary.mean = summary.sd = nan;
    summary.ci95 = {nan, nan};
    return;
  }
  const double rows = static_cast<double>(m.rows);
  const double shifted_mean = m.sum / rows;
  summary.mean = sampler.shift(o) + shifted_mean;
  summary.sd = m.rows > 1 ? std::sqrt(std::max(0.0, (m.sum2 - rows * shifted_mean * shifted_mean) / (rows - 1))) : 0.0;
  std::vector<double> replicate_means;
  for (const TaskSums& g : per_group) {
    if (g.moments[o].rows > 0) {
      replicate_means.push_back(sampler.shift(o) + g.moments[o].sum / static_cast<double>(g.moments[o].rows));
    }
  }
  const bool indicator = spec.kind == OutputKind::Indicator;
  const auto successes = static_cast<std::size_t>(std::llround(summary.mean * rows));
  if (indicator && (options.method == SamplingMethod::MonteCarlo || successes == 0 || successes == m.rows)) {
    summary.ci95 = wilson_interval(successes, m.rows);
  } else if (options.method == SamplingMethod::MonteCarlo) {
    const double half = 1.959963984540054 * summary.sd / std::sqrt(rows);
    summary.ci95 = {summary.mean - half, summary.mean + half};
  } else {
    summary.ci95 = replicate_interval(summary.mean, replicate_means);
    if (indicator) {
      // A replicate's estimate is a multiple of 1/n_g: identical replicates only show an error below that
      // resolution, so the interval is never narrower than ±1/n_g.
      const double resolution = static_cast<double>(per_group.size()) / rows;
      summary.ci95 = {std::max(0.0, std::min(summary.ci95.lo, summary.mean - resolution)),
                      std::min(1.0, std::max(summary.ci95.hi, summary.mean + resolution))};
    }
  }
}

// The first-order and total Sobol' indices of output o for each of the k inputs, with intervals from the replicates.
void describe_sobol_indices(std::size_t o, std::size_t k, const TaskSums& total, const std::vector<TaskSums>& per_group,
                            OutputSummary& summary) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < k; ++i) {
    const SobolSums& s = total.sobol[o * k + i];
    std::vector<double> first_replicates, total_replicates;
    for (const TaskSums& g : per_group) {
      const double f = first_order_index(g.sobol[o * k + i]), t = total_index(g.sobol[o * k + i]);
      if (std::isfinite(f)) first_replicates.push_back(f);
      if (std::isfinite(t)) total_replicates.push_back(t);
    }
    const double f = first_order_index(s), t = total_index(s);
    summary.first.push_back({f, std::isfinite(f) ? replicate_interval(f, first_replicates) : Interval{nan, nan}});
    summary.total.push_back({t, std::isfinite(t) ? replicate_interval(t, total_replicates) : Interval{nan, nan}});
  }
}

}  // namespace

PropagationResult propagate(const InputTransform& inputs, const Model& model, const PropagationOptions& options) {
  validate(inputs, model, options);
  const std::size_t k = inputs.size();
  const std::vector<OutputSpec>& specs = model.outputs();
  const std::size_t outputs = specs.size();
  const std::size_t n = options.samples;
  const std::size_t groups = std::min(kMaxGroups, n);
  const std::vector<Task> tasks = sample_tasks(n, groups);

  PropagationResult result;
  result.samples = n;
  result.groups = groups;
  result.evaluations = n * (options.sobol_indices ? k + 2 : 1);
  std::vector<std::size_t> stored_output;
  for (std::size_t o = 0; o < outputs; ++o) {
    if (specs[o].kind == OutputKind::Continuous) stored_output.push_back(o);
  }
  result.samples_of_output.assign(stored_output.size(), std::vector<double>(n));

  const Sampler sampler(inputs, model, options);
  std::vector<TaskSums> sums(tasks.size());
  const int threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  std::mutex progress_lock;  // the callback runs from one thread at a time, with fractions that never decrease
  std::size_t done = 0;
  std::atomic<bool> stopped = false;
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t t) {
      if (stopped.load(std::memory_order_relaxed)) return;
      sampler.run(tasks[t], sums[t], result.samples_of_output, stored_output);
      if (!options.progress) return;
      const std::lock_guard<std::mutex> lock(progress_lock);
      ++done;
      if (!stopped && !options.progress(static_cast<double>(done) / static_cast<double>(tasks.size()))) stopped = true;
    });
  });
  if (stopped) throw Interrupted();

  // Reduce in task order: per group, then the total (the same sums on any number of threads).
  const std::size_t sobol_terms = options.sobol_indices ? outputs * k : 0;
  std::vector<TaskSums> per_group(groups, empty_sums(outputs, sobol_terms));
  for (std::size_t t = 0; t < tasks.size(); ++t) add_sums(per_group[tasks[t].group], sums[t]);
  TaskSums total = empty_sums(outputs, sobol_terms);
  for (const TaskSums& g : per_group) add_sums(total, g);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::size_t stored_index = 0;
  for (std::size_t o = 0; o < outputs; ++o) {
    OutputSummary summary;
    summary.name = specs[o].name;
    summary.kind = specs[o].kind;
    describe_moments(sampler, o, specs[o], total, per_group, options, summary);
    if (specs[o].kind == OutputKind::Continuous) {
      summary.q05 = summary.q50 = summary.q95 = nan;
      describe_distribution(result.samples_of_output[stored_index++], options.histogram_bins, summary);
    }
    if (options.sobol_indices) describe_sobol_indices(o, k, total, per_group, summary);
    result.outputs.push_back(std::move(summary));
  }
  return result;
}

}  // namespace needlekit::uncertainty
