#include "needlekit/analysis/design_optimizer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <mutex>
#include <numeric>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "needlekit/analysis/design_point_evaluator.hpp"
#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {

std::string_view to_string(OptimizerStatus status) { return name_of(kOptimizerStatusNames, status); }

namespace {

constexpr double kTieTolerance = 1e-12;  // relative: values closer than this are ties, decided by loop order

// A grid point by its indices in loop order (n, D1, D2, D3, w, L) and its index value.
struct Point {
  std::size_t in = 0, i1 = 0, i2 = 0, i3 = 0, iw = 0, il = 0;
  double value = 0;
  auto key() const { return std::tie(in, i1, i2, i3, iw, il); }
};

// true if a is better than b: a larger value, or a tie and earlier in loop order (the first strict maximum).
bool better(const Point& a, const Point& b) {
  if (a.value > b.value * (1 + kTieTolerance)) return true;
  if (b.value > a.value * (1 + kTieTolerance)) return false;
  return a.key() < b.key();
}

// Keeps the best `capacity` points.
class TopPoints {
public:
  explicit TopPoints(std::size_t capacity) : capacity_(capacity) {}
  void offer(const Point& p) {
    if (points_.size() == capacity_ && !better(p, points_.back())) return;
    points_.insert(std::upper_bound(points_.begin(), points_.end(), p, better), p);
    if (points_.size() > capacity_) points_.pop_back();
  }
  void merge(const TopPoints& other) {
    for (const Point& p : other.points_) offer(p);
  }
  const std::vector<Point>& points() const { return points_; }

private:
  std::size_t capacity_;
  std::vector<Point> points_;
};

// Runs the progress callback from one thread at a time, with fractions that never decrease (a thread that counted
// its slice before another's may reach the lock after it: the smaller fraction is dropped); remembers a
// cancellation.
class Progress {
public:
  explicit Progress(const std::function<bool(double)>& callback) : callback_(callback) {}
  void report(double fraction) {
    if (!callback_) return;
    std::lock_guard lock(mutex_);
    if (fraction < last_fraction_) return;
    last_fraction_ = fraction;
    if (!callback_(fraction)) cancelled_ = true;
  }
  bool cancelled() const { return cancelled_.load(); }

private:
  const std::function<bool(double)>& callback_;
  std::mutex mutex_;
  double last_fraction_ = 0;  // guarded by mutex_
  std::atomic<bool> cancelled_{false};
};

// The pitch used in the index. The published-compatibility quirk (notes) belongs to the original engine's hollow
// cylinder/cone path only: its solid rows and its hollow bevel row (a separate "Bevel" path in Fig 6.20) use w/n.
double index_pitch(const DesignPointEvaluator& ev, std::size_t in, std::size_t iw, bool published_compat) {
  const bool quirk = published_compat && ev.space().hollow && ev.space().shape != needle::Shape::Bevel;
  return (quirk ? ev.w_values().back() : ev.w_values()[iw]) / ev.n_values()[in];
}

DesignCandidate make_candidate(const DesignPointEvaluator& ev, const Point& p, const OptimizerOptions& options) {
  DesignCandidate c;
  const needle::NeedleGeometry g = ev.geometry(p.i1, p.i2, p.i3, p.il);
  c.needles_per_row = static_cast<int>(std::lround(ev.n_values()[p.in]));
  c.tip_diameter = g.tip_diameter;
  c.base_diameter = g.base_diameter;
  c.bore_diameter = g.bore_diameter;
  c.width = ev.w_values()[p.iw];
  c.length = g.length;
  c.performance_index = p.value;

  ArrayDesign design{g, ev.space().material, c.needles_per_row, c.width};
  PerformanceIndexOptions pi_options;
  pi_options.buckling = options.buckling;
  pi_options.buckling_safety_factor = options.buckling_safety_factor;
  pi_options.spacing_factor = ev.space().spacing_factor;
  if (options.published_compat) pi_options.index_pitch = index_pitch(ev, p.in, p.iw, true);
  InsertionConditions conditions = ev.space().conditions;
  conditions.angle = 0;
  c.details = performance_index(design, conditions, pi_options);
  return c;
}

// ---- brute force -------------------------------------------------------------------------------------------------

OptimizerResult brute_force(const DesignPointEvaluator& ev, const OptimizerOptions& options, Progress& progress) {
  const std::size_t n1 = ev.d1_values().size(), n2 = ev.d2_count(), n3 = ev.d3_values().size();
  const std::size_t nw = ev.w_values().size(), nl = ev.l_values().size(), nn = ev.n_values().size();
  const bool cylinder = ev.space().shape == needle::Shape::Cylinder;

  // The needle-only table, in parallel.
  std::vector<DesignPointEvaluator::NeedleOutcome> table(n1 * n2 * n3 * nl);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n1 * n2), [&](const auto& range) {
    for (std::size_t pair = range.begin(); pair != range.end(); ++pair) {
      const std::size_t i1 = pair / n2, i2 = pair % n2;
      for (std::size_t i3 = 0; i3 < n3; ++i3)
        for (std::size_t il = 0; il < nl; ++il)
          table[((pair * n3) + i3) * nl + il] = ev.needle_outcome(i1, i2, i3, il);
    }
  });

  tbb::enumerable_thread_specific<TopPoints> tops([&] { return TopPoints(static_cast<std::size_t>(options.top)); });
  tbb::enumerable_thread_specific<std::uint64_t> feasible_counts(0);
  std::atomic<std::size_t> slices_done{0};
  const std::size_t slices = nn * n1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slices), [&](const auto& range) {
    TopPoints& top = tops.local();
    std::uint64_t& feasible = feasible_counts.local();
    for (std::size_t slice = range.begin(); slice != range.end(); ++slice) {
      if (progress.cancelled()) return;
      const std::size_t in = slice / n1, i1 = slice % n1;
      for (std::size_t i2 = 0; i2 < n2; ++i2) {
        const double d2 = cylinder ? ev.d1_values()[i1] : ev.d2_values()[i2];
        const std::size_t iw_min = ev.smallest_spacing_width(in, d2);
        for (std::size_t i3 = 0; i3 < n3; ++i3) {
          const auto* row = &table[(((i1 * n2) + i2) * n3 + i3) * nl];
          for (std::size_t iw = iw_min; iw < nw; ++iw) {
            const double pitch = index_pitch(ev, in, iw, options.published_compat);
            const double inv_pitch2 = 1.0 / (pitch * pitch);
            for (std::size_t il = 0; il < nl; ++il) {
              if (row[il].status != PointStatus::Feasible) continue;
              ++feasible;
              top.offer(Point{in, i1, i2, i3, iw, il, row[il].g * inv_pitch2});
            }
          }
        }
      }
      const std::size_t done = ++slices_done;
      if (done % 8 == 0 || done == slices) progress.report(static_cast<double>(done) / slices);
    }
  });

  OptimizerResult result;
  TopPoints merged(static_cast<std::size_t>(options.top));
  for (const TopPoints& t : tops) merged.merge(t);
  for (std::uint64_t f : feasible_counts) result.feasible += f;
  result.evaluated = static_cast<std::uint64_t>(nn) * n1 * n2 * n3 * nw * nl;
  result.needle_evaluations = table.size();
  if (progress.cancelled()) {
    result.status = OptimizerStatus::Cancelled;
    result.reason = "cancelled";
    return result;
  }
  for (const Point& p : merged.points()) result.top.push_back(make_candidate(ev, p, options));
  return result;
}

// ---- certified optimum -------------------------------------------------------------------------------------------

// The best pitch factor 1/pitch² over n for a base diameter, and the (n, w) indices that give it.
struct PitchChoice {
  double factor = 0;  // 1/pitch², 0 if no n fits
  std::size_t in = 0, iw = 0;
};

PitchChoice best_pitch(const DesignPointEvaluator& ev, double d2, bool published_compat) {
  PitchChoice best;
  for (std::size_t in = 0; in < ev.n_values().size(); ++in) {
    const std::size_t iw = ev.smallest_spacing_width(in, d2);
    if (iw == ev.w_values().size()) continue;
    const double pitch = index_pitch(ev, in, iw, published_compat);
    const double factor = 1.0 / (pitch * pitch);
    if (factor > best.factor * (1 + kTieTolerance)) best = {factor, in, iw};  // ties: the smaller n (first)
  }
  return best;
}

// Per (D1, D2) pair: the smallest feasible bore, the L index interval with L >= d + T, and an upper bound of the
// index over it that ignores buckling. φ (which may need an eigenvalue) is decided only for the pairs the bound
// cannot prune.
struct Pair {
  std::size_t i1 = 0, i2 = 0, i3 = 0, lo = 0, hi = 0;
  PitchChoice pitch;
  double bound = 0;
};

// The certified optimum by branch and bound: pairs in the order of their bounds, each searched over its L interval
// (cut where the needle starts to buckle) while its bound can beat the incumbent.
class CertifiedSearch {
public:
  CertifiedSearch(const DesignPointEvaluator& ev, const OptimizerOptions& options)
      : ev_(ev), options_(options), lengths_(ev.l_values()), cylinder_(ev.space().shape == needle::Shape::Cylinder),
        hollow_(ev.space().hollow) {}

  // The pairs that can hold a feasible design, with their bounds.
  std::vector<Pair> candidate_pairs() const {
    const std::size_t n1 = ev_.d1_values().size(), n2 = ev_.d2_count();
    const double target = ev_.space().conditions.target_depth;
    // Per base diameter: the best (n, w).
    std::vector<PitchChoice> pitch(n2);
    for (std::size_t i2 = 0; i2 < n2; ++i2) {
      pitch[i2] = best_pitch(ev_, cylinder_ ? 0.0 : ev_.d2_values()[i2], options_.published_compat);
    }
    std::vector<Pair> pairs(n1 * n2);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n1 * n2), [&](const auto& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        Pair& p = pairs[k];
        p.i1 = k / n2;
        p.i2 = k % n2;
        p.pitch = cylinder_ ? best_pitch(ev_, ev_.d1_values()[p.i1], options_.published_compat) : pitch[p.i2];
        if (p.pitch.factor == 0) continue;
        const needle::NeedleGeometry g0 = ev_.geometry(p.i1, p.i2, 0, 0);
        if (!cylinder_ && !(g0.tip_diameter < g0.base_diameter)) continue;
        if (cylinder_ && ev_.needle_outcome(p.i1, 0, 0, 0).status == PointStatus::InvalidGeometry) continue;
        if (hollow_ && !(ev_.d3_values().front() < std::min(g0.tip_diameter, g0.base_diameter))) continue;
        p.i3 = 0;  // the smallest bore is always the best: it only weakens the column
        const double d = ev_.deformation(p.i1, p.i2);
        p.lo = static_cast<std::size_t>(std::lower_bound(lengths_.begin(), lengths_.end(), d + target) -
                                        lengths_.begin());
        if (p.lo == lengths_.size()) continue;
        p.hi = lengths_.size() - 1;
        p.bound = bound_on(p, p.lo, p.hi);
      }
    });
    return pairs;
  }

  // g = Q/H with Q = V(h)/h non-decreasing (the mean of a non-decreasing section area) and V non-decreasing:
  // solid (H = T): g <= Q(h_b)/T on [h_a, h_b]; hollow (H = h): g <= V(h_b)/h_a².
  double bound_on(const Pair& p, std::size_t a, std::size_t b) const {
    const double d = ev_.deformation(p.i1, p.i2);
    const needle::NeedleGeometry gb = ev_.geometry(p.i1, p.i2, p.i3, b);
    const double h_a = lengths_[a] - d, h_b = lengths_[b] - d;
    return p.pitch.factor * (hollow_ ? ev_.embedded(gb, h_b) / (h_a * h_a) : ev_.g_of(gb, d));
  }

  bool cannot_beat(double bound) const { return incumbent_ && bound < incumbent_->value * (1 - kTieTolerance); }

  // One pair: φ holds on a prefix of the L grid (P_cr decreases with L), found by binary search; then branch and
  // bound over that L index interval.
  void search(Pair p) {
    if (ev_.needle_buckles(p.i1, p.i2, p.i3, lengths_[p.lo])) return;
    std::size_t ok = p.lo, bad = lengths_.size();
    while (bad - ok > 1) {
      const std::size_t mid = ok + (bad - ok) / 2;
      (ev_.needle_buckles(p.i1, p.i2, p.i3, lengths_[mid]) ? bad : ok) = mid;
      ++needle_evaluations_;
    }
    p.hi = ok;
    const double d = ev_.deformation(p.i1, p.i2);
    std::vector<std::pair<std::size_t, std::size_t>> stack{{p.lo, p.hi}};
    while (!stack.empty()) {
      const auto [a, b] = stack.back();
      stack.pop_back();
      if (cannot_beat(bound_on(p, a, b))) continue;
      if (b - a < 8) {
        for (std::size_t il = a; il <= b; ++il) {
          const double value = p.pitch.factor * ev_.g_of(ev_.geometry(p.i1, p.i2, p.i3, il), d);
          ++evaluated_;
          const Point candidate{p.pitch.in, p.i1, p.i2, p.i3, p.pitch.iw, il, value};
          if (!incumbent_ || better(candidate, *incumbent_)) incumbent_ = candidate;
        }
        continue;
      }
      const std::size_t mid = a + (b - a) / 2;
      stack.push_back({mid + 1, b});  // explored second
      stack.push_back({a, mid});      // explored first
    }
  }

  void count_needles(std::uint64_t n) { needle_evaluations_ += n; }
  std::uint64_t evaluated() const { return evaluated_; }
  std::uint64_t needle_evaluations() const { return needle_evaluations_ + evaluated_; }
  const std::optional<Point>& incumbent() const { return incumbent_; }

private:
  const DesignPointEvaluator& ev_;
  const OptimizerOptions& options_;
  const std::vector<double>& lengths_;
  const bool cylinder_, hollow_;
  std::optional<Point> incumbent_;
  std::uint64_t evaluated_ = 0, needle_evaluations_ = 0;
};

OptimizerResult certified(const DesignPointEvaluator& ev, const OptimizerOptions& options, Progress& progress) {
  CertifiedSearch search(ev, options);
  const std::vector<Pair> pairs = search.candidate_pairs();
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (pairs[k].bound > 0) order.push_back(k);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return pairs[a].bound > pairs[b].bound; });
  search.count_needles(order.size());
  for (std::size_t idx = 0; idx < order.size(); ++idx) {
    const Pair& p = pairs[order[idx]];
    if (search.cannot_beat(p.bound)) break;  // sorted: no later pair can beat it either
    if (idx % 256 == 0) {
      progress.report(static_cast<double>(idx) / order.size());
      if (progress.cancelled()) break;
    }
    search.search(p);
  }
  OptimizerResult result;
  result.evaluated = search.evaluated();
  result.needle_evaluations = search.needle_evaluations();
  if (progress.cancelled()) {
    result.status = OptimizerStatus::Cancelled;
    result.reason = "cancelled";
    return result;
  }
  progress.report(1.0);
  if (search.incumbent()) result.top.push_back(make_candidate(ev, *search.incumbent(), options));
  return result;
}

}  // namespace

double optimizer_memory_bytes(const DesignSpace& space, SearchMethod method) {
  const auto count = [](const GridRange& range, std::string_view key) {
    return static_cast<double>(grid_count(range, key));
  };
  const bool cylinder = space.shape == needle::Shape::Cylinder;
  const double n = count(space.needles_per_row, "needles_per_row"), d1 = count(space.tip_diameter, "tip_diameter");
  const double d2 = cylinder ? 1 : count(space.base_diameter, "base_diameter");
  const double d3 = space.hollow ? count(space.bore_diameter, "bore_diameter") : 1;
  const double w = count(space.width, "width"), l = count(space.length, "length");
  const double pairs = d1 * d2;
  // certified(): a Pair (five indices, a PitchChoice and a bound: 80 bytes) and an index in `order` per pair.
  constexpr double kCertifiedBytesPerPair = 88;
  return 8 * (n + d1 + d2 + d3 + w + l) + 16 * pairs + 8 * pairs * d3 +
         (method == SearchMethod::Certified ? kCertifiedBytesPerPair * pairs : 0);
}

OptimizerResult optimize_design(const DesignSpace& space, const OptimizerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.top < 1) throw InvalidInput(fmt::format("top: {} must be >= 1", options.top));
  if (!(space.spacing_factor >= 0)) throw InvalidInput("spacing_factor: must be >= 0");
  if (!(space.conditions.target_depth > 0)) throw InvalidInput("target_depth: must be a positive length");
  const std::uint64_t points = design_space_size(space);
  if (options.method == SearchMethod::BruteForce && points > options.max_brute_force_points) {
    throw InvalidInput(fmt::format("ranges: the design space has {:.3g} points, more than the brute-force limit of "
                                   "{:.3g} (about {:.0f} s at 1e8 points/s); use the certified method (--certified) "
                                   "or raise the limit (--max-grid-points)",
                                   static_cast<double>(points), static_cast<double>(options.max_brute_force_points),
                                   static_cast<double>(points) / 1e8));
  }
  if (const double bytes = optimizer_memory_bytes(space, options.method); !(bytes <= options.max_memory_bytes)) {
    throw InvalidInput(fmt::format("ranges: the design space's tables would take about {:.3g} GiB ({} D1 x {} D2 "
                                   "values), more than the limit of {:.3g} GiB; expected coarser steps for "
                                   "tip_diameter and base_diameter, or raise the limit (--max-memory-gib)",
                                   bytes / (1ULL << 30), grid_count(space.tip_diameter, "tip_diameter"),
                                   space.shape == needle::Shape::Cylinder
                                       ? 1
                                       : grid_count(space.base_diameter, "base_diameter"),
                                   options.max_memory_bytes / (1ULL << 30)));
  }
  const DesignPointEvaluator evaluator(space, options.buckling, options.buckling_safety_factor);
  Progress progress(options.progress);

  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  OptimizerResult result;
  arena.execute([&] {
    result = options.method == SearchMethod::BruteForce ? brute_force(evaluator, options, progress)
                                                        : certified(evaluator, options, progress);
  });
  result.grid_points = points;
  if (result.status != OptimizerStatus::Cancelled) {
    if (result.top.empty()) {
      result.status = OptimizerStatus::Infeasible;
      result.reason = "no design in the space satisfies every constraint (L >= d + T, no buckling, D3 < D1 < D2, "
                      "w >= beta*n*D2)";
    } else {
      result.status = OptimizerStatus::Optimal;
    }
  }
  for (const DesignCandidate& candidate : result.top)
    result.top_outside_force_law_range += !candidate.details.puncture_force_in_range;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace needlekit::analysis
