// Elastic buckling load of a column whose flexural rigidity EI(s) varies along its length: the lowest eigenvalue of
// the column equation. Used for tapered (cone) and bevel needles, whose load the dissertation takes from a table
// (Eq 2.36, m "depending on I1/I2", Timoshenko 1961) or from SolidWorks (bevel).
#pragma once
#include <functional>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::analysis {

enum class EndCondition {
  FixedFree,    // base clamped, tip free (the dissertation's default, K = 2)
  FixedPinned,  // base clamped, tip pinned (K = 0.7)
  FixedFixed,   // both clamped (K = 0.5)
};
inline constexpr EnumTable<EndCondition, 3> kEndConditionNames{{
    {EndCondition::FixedFree, "fixed-free", "base clamped, tip free (the dissertation's, K = 2)"},
    {EndCondition::FixedPinned, "fixed-pinned", "base clamped, tip pinned (K = 0.7)"},
    {EndCondition::FixedFixed, "fixed-fixed", "both ends clamped (K = 0.5)"},
}};

struct ColumnEigenvalueOptions {
  EndCondition end_condition = EndCondition::FixedFree;
  int intervals = 100;      // grid intervals along the column; the result is Richardson-extrapolated from n and 2n
};

// Lowest buckling load P (N) of a column of length L (m) with flexural rigidity EI(s) (N·m²) given as a function of
// the distance s ∈ [0, L] from the loaded (tip) end; the base s = L is clamped.
//   FixedFree: EI(s)·u'' + P·u = 0 with u(0) = 0, u'(L) = 0 (u = tip deflection minus deflection: the moment at s
//   is P·u), discretised by second-order finite differences into a symmetric tridiagonal pencil and solved by
//   inverse iteration; other end conditions: (EI w'')'' + P w'' = 0 by Hermite-cubic beam elements and a dense
//   generalized eigen solve.
// EI must be positive on (0, L].
double column_buckling_load(const std::function<double(double)>& flexural_rigidity, double length,
                            const ColumnEigenvalueOptions& options = {});

}  // namespace needlekit::analysis
