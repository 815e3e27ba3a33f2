// A design-space file with min_success_probability (io/design_config.hpp: RobustSpec) run and presented as
// `needlekit optimize --json` and `needlekit serve`'s POST /api/optimize answer it: one place for the options and the
// JSON, so that the two answers cannot drift apart.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>

#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/io/design_config.hpp"

namespace needlekit::io {

struct RobustDesignRunOptions {
  analysis::OptimizerOptions optimizer;   // the nominal ranking's limits (robust_design ranks by brute force)
  int top = 10;                           // >= 1: designs listed in "top" (all the ranked ones were candidates)
  int threads = 0;                        // >= 0: sampling threads, 0: all hardware threads
  std::function<bool(double)> progress;   // uncertainty::RobustDesignOptions::progress
};

// robust_design_json() of uncertainty::robust_design() for the file's space and RobustSpec, with "top" cut to
// options.top designs. Throws InvalidInput for a file without min_success_probability and as robust_design;
// Interrupted when the progress callback returns false.
nlohmann::json robust_design_run_json(const SpaceFile& file, const RobustDesignRunOptions& options);

}  // namespace needlekit::io
