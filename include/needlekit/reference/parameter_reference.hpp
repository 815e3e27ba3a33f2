// Every parameter table of the library (core/parameter.hpp) as text, with the defaults that apply where the
// parameters are written: what `needlekit describe KEY | --all` prints and what docs/reference.md holds (generated
// by `needlekit describe --all --markdown`; a test fails when the file is out of date).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/parameter_text.hpp"

namespace needlekit::reference {

struct ParameterGroup {
  std::string_view title;    // where the keys are written, e.g. "indentation cases, [model] and [solver]"
  std::string_view options;  // the struct in C++ and Python, e.g. "SolverOptions"
  std::vector<ParameterText> parameters;
};

std::vector<ParameterGroup> parameter_reference();

// The dotted keys of every parameter ("model.law", "solver.friction", ...).
std::vector<std::string> parameter_keys();
// "solver.friction\n  meaning\n  kind: ...\n" as `needlekit describe KEY` prints it; throws InvalidInput listing the
// keys when there is no such key.
std::string described(std::string_view key);
// Every parameter so, under a heading per group (`needlekit describe --all`).
std::string described_all();
// docs/reference.md.
std::string reference_markdown();

}  // namespace needlekit::reference
