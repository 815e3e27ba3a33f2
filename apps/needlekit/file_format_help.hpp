// The input-file formats with units and valid ranges, shown at the end of the commands' --help.
#pragma once
#include <fmt/format.h>

#include <string>

#include "needlekit/analysis/puncture_force_law.hpp"

namespace needlekit::cli {

inline constexpr const char* kDesignFileHelp = R"(DESIGN file (TOML; every dimensional value is a string with its unit, a bare number is an error):
  [needle]     shape = "cylinder" | "cone" | "bevel"
               tip_diameter = "30 um"      D1 > 0 (bevel: sagitta of the tip segment)
               base_diameter = "150 um"    D2 >= D1 (cone and bevel D1 < D2 in the optimizer; cylinder: omit, = D1)
               bore_diameter = "20 um"     0 < D3 < D1; omit for a solid needle
               length = "500 um"           L > 0
               material = "silicon"        a preset (see `needlekit materials`) or { youngs_modulus = "4 GPa",
                                           yield_strength = "60 MPa", allowable_stress = "40 MPa", name = "..." }
  [array]      needles_per_row = 10        n >= 1 (n x n needles)
               width = "1 cm"              w > 0, patch width
               spacing_factor = 3          beta >= 0 of w >= beta*n*D2 (default 3; 0 disables)
  [tissue]     model = "skin"              "skin" | "brain" | { alpha = "0.0183 N", tau = "6.25 /mm",
                                           small_tip_slope = "0.0608 /um" }   (default skin)
               puncture_force = "eq-4.2"   the puncture-force law F(A), laws below (default eq-4.2)
  [insertion]  angle = "0 deg"             [0, 90) deg from the surface normal (default 0)
               target_depth = "50 um"      T > 0, or application = "transdermal" (50 um) | "aesthetic" | "tattoo"
                                           (1.5 mm) | "brain" (1 mm); default transdermal
               buckling_safety_factor = 1, bending_safety_factor = 1   (>= 1)
               end_condition = "fixed-free" | "fixed-pinned" | "fixed-fixed"   (default fixed-free)
               effective_length = "theoretical" | "practical", johnson = true (Johnson formula for short columns))";

inline constexpr const char* kSpaceFileHelp = R"(SPACE file (TOML; every dimensional value is a string with its unit):
  shape = "cone"                 "cylinder" | "cone" | "bevel"
  hollow = false                 true: a bore_diameter range is required
  material = "silicon"           a preset (see `needlekit materials`) or { youngs_modulus = "169 GPa", ... }
  tissue = "skin"                "skin" | "brain" | { alpha = "0.0183 N", tau = "6.25 /mm" }   (default skin)
  puncture_force = "eq-4.2"      the puncture-force law F(A), laws below (default eq-4.2)
  target_depth = "50 um"         T > 0 (default 50 um)
  spacing_factor = 3             beta >= 0 of w >= beta*n*D2 (default 3)
  [ranges]                       inclusive [min, max, step], min > 0, max >= min, step > 0
  needles_per_row = [5, 25, 1]   integers
  tip_diameter = ["30 um", "150 um", "10 um"]
  base_diameter = ["30 um", "300 um", "10 um"]   (a cylinder omits it: D2 = D1)
  bore_diameter = ["20 um", "50 um", "10 um"]    (hollow only)
  width = ["5000 um", "10000 um", "1000 um"]
  length = ["300 um", "500 um", "50 um"])";

inline constexpr const char* kRobustSpaceHelp = R"(Robust design (optional): add
  min_success_probability = 0.99 the best nominal design whose P(success) under [uncertain] is at least this
  [uncertain], [sampling], [[correlation]]   as in `needlekit uncertainty --help`; a design variable (tip_diameter,
                                 base_diameter, bore_diameter, length, width) takes no mean: its spread is centred
                                 on every candidate. The best max 2000 nominal designs are checked, best first.)";

inline constexpr const char* kUncertaintyFileHelp = R"(UQ file: a DESIGN file (below) plus
  [uncertain]    one inline table per uncertain input, keyed by its design-file key, values with the input's unit:
                 "needle.tip_diameter" = { distribution = "normal", mean = "30 um", sd = "2 um" }
                 "tissue.alpha" = { distribution = "lognormal", median = "0.0183 N", sigma_log = 0.2 }
                 an omitted mean / median is the design's value. More than 0.1 % of a distribution outside the
                 input's physical range (e.g. a diameter <= 0) is an error; less is truncated and reported.
  [sampling]     samples = 4096 (>= 2), method (below, default "sobol"), seed = 1, sobol_indices = true
                 (N*(k+2) runs for k inputs)
  [[correlation]] inputs = ["tissue.alpha", "tissue.tau"], rho = 0.5   (between normal scores, optional))";
// The puncture-force laws of [tissue] puncture_force, from the law table (analysis::puncture_force_laws()).
inline std::string puncture_force_law_help() {
  std::string help = "\nPuncture-force laws (puncture_force = NAME, or a table { law = NAME, ... } for the user laws; D = the "
                     "tip's equivalent diameter sqrt(4A/pi)):\n";
  for (const auto& law : analysis::puncture_force_laws())
    help += fmt::format("  {:<16}{}\n  {:<16}  source: {}\n", law.name, law.meaning, "", law.source);
  help += "  linear-area: slope = \"0.00019 N/um2\", intercept = \"-0.66 N\"; linear-diameter: slope = \"4594 N/m\", "
          "intercept = \"-3 mN\";\n  table: tip_diameter = [\"5 um\", \"37 um\"], force = [\"20 mN\", \"167 mN\"]; "
          "any law: valid_tip_diameter = [\"min\", \"max\"]\n  Outside a law's validity range the result carries a note.";
  return help;
}

inline std::string design_file_help() { return std::string(kDesignFileHelp) + "\n" + puncture_force_law_help(); }
inline std::string space_file_help() { return std::string(kSpaceFileHelp) + "\n" + puncture_force_law_help(); }

}  // namespace needlekit::cli
