// Fast evaluation of the performance index at the points of a DesignSpace grid, shared by the brute-force and the
// certified optimizers. The index factorises (Eqs 4.25, 5.9 with θ = 0):
//   PI(n, D1, D2, D3, w, L) = φ(D1, D2, D3, L) · g(D1, D2, L) / pitch(n, w)²,   g = Q/H,
// so the needle-only part is evaluated once per needle and the pitch part is arithmetic. The tapered-column factor
// m of Eq 2.36 depends only on the section shape (D1, D2, D3), not on L, and is memoized per grid triple; it is
// computed only when cheap bounds cannot decide φ (see needle_buckles()).
#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "needlekit/analysis/design_space.hpp"

namespace needlekit::analysis {

// Why a grid point has a zero index (first failed check in this order).
enum class PointStatus : std::uint8_t {
  Feasible,
  InvalidGeometry,   // D1 >= D2 (cone, bevel: strict, notes), D1 != D2 (cylinder), D3 >= D1 or D3 >= D2
  TooShort,          // L < d + T
  Buckles,           // F >= P_cr
  SpacingViolated,   // w < β·n·D2
};

class DesignPointEvaluator {
public:
  DesignPointEvaluator(const DesignSpace& space, const BucklingOptions& buckling, double buckling_safety_factor);

  const DesignSpace& space() const { return space_; }
  const std::vector<double>& n_values() const { return n_; }
  const std::vector<double>& d1_values() const { return d1_; }
  const std::vector<double>& d2_values() const { return d2_; }
  const std::vector<double>& d3_values() const { return d3_; }  // {0} for solid needles
  const std::vector<double>& w_values() const { return w_; }
  const std::vector<double>& l_values() const { return l_; }

  // Geometry of grid indices; for cylinders D2 is D1 (the D2 grid is not used: index i2 must be 0).
  needle::NeedleGeometry geometry(std::size_t i1, std::size_t i2, std::size_t i3, std::size_t il) const;
  std::size_t d2_count() const;

  struct NeedleOutcome {
    PointStatus status = PointStatus::Feasible;
    double g = 0;  // Q/H (m), the needle part of the index; 0 unless feasible
  };
  // The needle-only part at grid indices (thread-safe).
  NeedleOutcome needle_outcome(std::size_t i1, std::size_t i2, std::size_t i3, std::size_t il) const;

  // φ = 0? (thread-safe; memoizes m per (i1, i2, i3)).
  bool needle_buckles(std::size_t i1, std::size_t i2, std::size_t i3, double length) const;

  // The puncture-related quantities depend on (i1, i2) only.
  double deformation(std::size_t i1, std::size_t i2) const;
  double buckling_force(std::size_t i1, std::size_t i2) const;

  // Smallest grid width index with w >= β·n·D2, or w_values().size() if none.
  std::size_t smallest_spacing_width(std::size_t in, double base_diameter) const;

  // g for a cutting depth h (helper of the certified bound): Q(h)/H(h).
  double g_of(const needle::NeedleGeometry& needle, double deformation) const;
  // Embedded volume at h (non-decreasing in h), for the certified bound.
  double embedded(const needle::NeedleGeometry& needle, double h) const;

private:
  double tapered_factor(std::size_t i1, std::size_t i2, std::size_t i3) const;

  DesignSpace space_;
  BucklingOptions buckling_;
  double safety_factor_;
  std::vector<double> n_, d1_, d2_, d3_, w_, l_;
  std::vector<double> deformation_, force_;                 // per (i1, i2)
  mutable std::unique_ptr<std::atomic<double>[]> m_cache_;  // per (i1, i2, i3); NaN = not computed
};

}  // namespace needlekit::analysis
