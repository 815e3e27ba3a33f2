// The design optimizer of dissertation §4.8 (Fig 4.12, Fig 6.20, Table 6.3): the array of one needle type that
// maximises the performance index over a grid of n, D1, D2, D3, w, L.
//
// Two methods:
//  - BruteForce: every grid point, in the dissertation's loop order n, D1, D2, D3, w, L; ties go to the first point
//    in that order (values within a relative 1e-12 are ties). Multi-threaded; reports the top K designs.
//  - Certified: the same optimum without enumerating the grid, for grids far too fine to enumerate (1 µm steps):
//    the index factorises as φ·g(D1, D2, L)·p(n, w, D2) (see design_point_evaluator.hpp), the best w for a given
//    (n, D2) is the smallest grid width with w >= β·n·D2, the smallest feasible bore is always best (it only weakens
//    the column), φ is monotone in L, and the embedded volume is non-decreasing in the cutting depth. A
//    branch-and-bound over (D1, D2) pairs and L intervals with these bounds prunes everything that cannot reach the
//    incumbent; the answer is the brute-force answer (tested on grids where brute force is feasible).
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/analysis/design_space.hpp"
#include "needlekit/core/limits.hpp"

namespace needlekit::analysis {

enum class SearchMethod { BruteForce, Certified };
inline constexpr EnumTable<SearchMethod, 2> kSearchMethodNames{{
    {SearchMethod::BruteForce, "brute-force", "every point of the design grid"},
    {SearchMethod::Certified, "certified", "branch and bound with certified bounds"},
}};

struct OptimizerOptions {
  SearchMethod method = SearchMethod::BruteForce;
  int top = 10;                    // designs to report (brute force), >= 1
  // Reproduce Table 6.3's hollow cylinder and hollow cone rows: for those two types the index uses the pitch
  // w_max/n while the constraint and the reported w use the loop's w (notes, "Compatibility quirk"). The other four
  // rows of Table 6.3 use w/n and are unaffected.
  bool published_compat = false;
  int threads = 0;                 // 0: all hardware threads
  BucklingOptions buckling;
  double buckling_safety_factor = 1.0;
  // Brute force refuses spaces larger than this (use the certified method, or raise it).
  std::uint64_t max_brute_force_points = limits::kMaxBruteForcePoints;
  // Both methods refuse spaces whose tables (optimizer_memory_bytes) would take more than this many bytes.
  double max_memory_bytes = limits::kMaxOptimizerMemoryBytes;
  // Called with the fraction done in [0, 1] from one thread at a time; return false to cancel.
  std::function<bool(double)> progress;
};

struct DesignCandidate {
  int needles_per_row = 0;
  double tip_diameter = 0;   // m
  double base_diameter = 0;  // m
  double bore_diameter = 0;  // m (0: solid)
  double width = 0;          // m
  double length = 0;         // m
  double performance_index = 0;  // 1/m
  PerformanceIndexResult details;  // every intermediate quantity (performance_index() of this design)
};

enum class OptimizerStatus { Optimal, Infeasible, Cancelled };
inline constexpr EnumTable<OptimizerStatus, 3> kOptimizerStatusNames{{
    {OptimizerStatus::Optimal, "optimal", "the best feasible design was found"},
    {OptimizerStatus::Infeasible, "infeasible", "no design of the space is feasible"},
    {OptimizerStatus::Cancelled, "cancelled", "the search was stopped before it finished"},
}};
std::string_view to_string(OptimizerStatus status);

struct OptimizerResult {
  OptimizerStatus status = OptimizerStatus::Infeasible;
  std::string reason;                 // for Infeasible/Cancelled
  std::vector<DesignCandidate> top;   // best first; top[0] is the optimum (certified: only the optimum)
  std::uint64_t grid_points = 0;      // size of the design space
  std::uint64_t evaluated = 0;        // points whose index was evaluated (brute force: all)
  std::uint64_t feasible = 0;         // evaluated points with index > 0 (certified: not counted, 0)
  std::uint64_t needle_evaluations = 0;  // needle-only evaluations (both methods)
  // Designs of `top` whose tip lies outside the puncture-force law's validity range (their force is extrapolated;
  // each one's details.notes says why).
  int top_outside_force_law_range = 0;
  double seconds = 0;                 // wall time
};

// Throws InvalidInput for invalid spaces (ranges, material, tissue), a brute-force space larger than
// options.max_brute_force_points, or one whose tables would exceed options.max_memory_bytes; all before any work.
OptimizerResult optimize_design(const DesignSpace& space, const OptimizerOptions& options = {});

// The bytes the optimizer allocates for a space: the grid values of every axis, two doubles per (D1, D2) pair and
// one per (D1, D2, D3) triple (DesignPointEvaluator), and for the certified method its per-pair bounds and order.
// Throws InvalidInput for invalid ranges.
double optimizer_memory_bytes(const DesignSpace& space, SearchMethod method);

}  // namespace needlekit::analysis
