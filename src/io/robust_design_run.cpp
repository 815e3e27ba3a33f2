#include "needlekit/io/robust_design_run.hpp"

#include <algorithm>
#include <iterator>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "needlekit/uncertainty/robust_design.hpp"

namespace needlekit::io {

nlohmann::json robust_design_run_json(const SpaceFile& file, const RobustDesignRunOptions& options) {
  if (!file.robust) throw InvalidInput("robust design: the space has no min_success_probability");
  uncertainty::RobustDesignOptions robust;
  robust.min_success_probability = file.robust->min_success_probability;
  robust.sampling = file.robust->sampling;
  robust.sampling.threads = options.threads;
  robust.optimizer = options.optimizer;
  robust.optimizer.progress = nullptr;
  robust.progress = options.progress;
  const uncertainty::RobustDesignResult result =
      uncertainty::robust_design(file.space, file.robust->inputs, file.robust->correlations, robust);
  nlohmann::json json = robust_design_json(file.space, robust, result);
  nlohmann::json& top = json["top"];
  top.erase(top.begin() + std::min<std::ptrdiff_t>(options.top, std::ssize(top)), top.end());
  return json;
}

}  // namespace needlekit::io
