// One design file evaluated as `needlekit evaluate` and `needlekit serve`'s POST /api/evaluate present it: the
// performance index with every intermediate quantity, the needle's implausible-scale warnings (also in the result's
// notes), and the JSON both print. One function, so that the two answers cannot drift apart.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/io/design_config.hpp"

namespace needlekit::io {

struct DesignEvaluation {
  analysis::PerformanceIndexResult result;  // performance_index(), the warnings appended to its notes
  std::vector<std::string> warnings;        // needle_scale_warnings() of the design's needle
  nlohmann::json json;                      // performance_json(): what `needlekit evaluate --json` prints
};

DesignEvaluation evaluate_design(const DesignFile& file);

}  // namespace needlekit::io
