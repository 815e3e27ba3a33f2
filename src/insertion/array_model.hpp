// The model run_indentation solves for a case, and the map from its per-needle results back to the case's needles:
// the identity, or for a symmetric needle array its reduced model (insertion/needle_array.hpp).
#pragma once
#include <optional>
#include <vector>

#include "needlekit/insertion/indentation.hpp"

namespace needlekit::insertion::detail {

struct ArrayModel {
  std::optional<IndentationCase> reduced;  // the half or quarter model; empty: the case itself is solved
  std::vector<int> source;                 // per needle of the case: its needle in the solved model
  std::vector<double> multiplicity;        // per needle of the case: its force / its solved needle's force (1, 2, 4)
  double factor = 1;                       // totals of the case / totals of the solved model (1, 2, 4)
};

ArrayModel array_model(const IndentationCase& indentation_case);

// Throws InvalidInput naming the key, for a case with an array: the array's own checks (needle_array.hpp), needles
// that are not the array's, a block smaller than its footprint, a symmetry with a tissue mesh file or another
// boundary condition than the sides and bottom fixed, a backing plate that the depth would press onto the tissue.
void validate_array_case(const IndentationCase& indentation_case);

// A converged step of the solved model as the case's: totals times `factor`, one force and contact area per needle
// of the case (the contact nodes stay the solved model's).
IndentationStep whole_step(const IndentationStep& solved, const ArrayModel& model);

}  // namespace needlekit::insertion::detail
