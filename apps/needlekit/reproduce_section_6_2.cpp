// §6.2 of `needlekit reproduce`: force-depth curves of the sharp bevel, blunt bevel and cylinder in silicone rubber
// (pre- and post-puncture), the puncture points against the experiments, the four-needle array of Fig 6.3 and soft
// vs layered tissue (Fig 6.4).
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {

SectionReport section_6_2(const RunContext& /*context*/, const SectionProgress& progress) {
  SectionReport report("6.2", "§6.2 Pre-puncture, puncture and post-puncture insertion forces");
  report.unavailable("not available in this build: the FE indentation and post-puncture capabilities (issues 3 and "
                     "4) are not part of it");
  progress(1, "done");
  return report;
}

}  // namespace needlekit::cli::reproduce
