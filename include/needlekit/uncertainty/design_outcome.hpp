// The events and the performance index of one sampled design, fast enough for 10⁶ samples: the same quantities and
// decisions as analysis::performance_index() (Eqs 4.2–4.5, 4.23, 4.25, 5.3–5.9), without its text and notes, and
// with the expensive section-shape factors computed once for the nominal section:
//   P_cr = m·E·I2/L² (Eq 2.36) where m depends only on the section's profile in s/L, so it holds for any E and L
//   as long as D1, D2, D3 are the nominal ones; likewise P_Be = σ·min S(s)/s scales as σ/L (Eqs 5.7, 5.8).
// A sample with other diameters gets its own eigenvalue (slower). tests/unit/test_design_outcome.cpp checks the
// agreement with performance_index() over random designs.
#pragma once
#include <optional>

#include "needlekit/needle/section_properties.hpp"
#include "needlekit/uncertainty/design_inputs.hpp"

namespace needlekit::uncertainty {

struct DesignOutcome {
  bool valid = true;            // false: the sampled values make no valid needle (e.g. D1 > D2); nothing else is set
  bool punctures = false;       // |F(A)| > 0 and cutting depth h = L − d > 0 (Eqs 4.2–4.4)
  bool buckles = false;         // φ = 0: SF·|F|/cos θ >= P_cr (Eqs 4.5, 5.3)
  std::optional<bool> bends;    // ω = 0: SF·|F|·tan θ >= P_Be (Eq 5.4); empty when not assessed (no allowable stress, θ > 0)
  bool reaches_target = false;  // L >= d + T (Eq 4.23)
  bool spacing_ok = true;       // w >= β·n·D2 (§4.8)
  double performance_index = 0; // 1/m, Eq 4.25 / 5.9 (0 when any check fails)
};

class DesignOutcomeEvaluator {
public:
  // Throws InvalidInput as performance_index() for an invalid nominal case.
  explicit DesignOutcomeEvaluator(const DesignCase& nominal);

  const DesignValues& nominal() const { return nominal_; }
  // Thread-safe.
  DesignOutcome operator()(const DesignValues& values) const;

private:
  bool nominal_section(const needle::NeedleGeometry& needle) const;
  double critical_buckling_load(const DesignValues& values) const;
  bool buckles(const DesignValues& values, double demand) const;  // demand >= P_cr, by bounds where they decide
  double critical_bending_load(const DesignValues& values) const;

  DesignValues nominal_;
  analysis::PerformanceIndexOptions options_;
  double tip_area_ = 0;          // A of the nominal section
  needle::SectionProperties base_section_;  // at the base, of the nominal section
  double tapered_factor_ = 0;    // m of the nominal section (cones, bevels)
  double bending_factor_ = 0;    // P_Be·L/σ of the nominal section
};

}  // namespace needlekit::uncertainty
