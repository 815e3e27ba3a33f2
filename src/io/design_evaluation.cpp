#include "needlekit/io/design_evaluation.hpp"

#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/scale_warnings.hpp"

namespace needlekit::io {

DesignEvaluation evaluate_design(const DesignFile& file) {
  DesignEvaluation evaluation;
  evaluation.result = analysis::performance_index(file.design, file.conditions, file.options);
  evaluation.warnings = needle_scale_warnings(file.design.needle);
  evaluation.result.notes.insert(evaluation.result.notes.end(), evaluation.warnings.begin(),
                                 evaluation.warnings.end());
  evaluation.json = performance_json(file.design, evaluation.result);
  return evaluation;
}

}  // namespace needlekit::io
