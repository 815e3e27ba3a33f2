// The sections of `needlekit reproduce`, one source file each: every section runs its examples of dissertation
// Chapter 6 through the library, writes its data files under the run's staging folder and returns its report.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "reproduce_report.hpp"

namespace needlekit::cli::reproduce {

// Progress of one section: the fraction of the section done, in [0, 1], and what it is doing.
using SectionProgress = std::function<void(double fraction, const std::string& step)>;

SectionReport section_6_2(const RunContext& context, const SectionProgress& progress);  // reproduce_section_6_2.cpp
// The §6.2 rows after calibration (reproduce_section_6_2_calibrated.cpp; full run only).
void calibrated_phantom(const RunContext& context, SectionReport& report, const SectionProgress& progress);
SectionReport section_6_3(const RunContext& context, const SectionProgress& progress);  // reproduce_section_6_3.cpp
SectionReport section_6_4(const RunContext& context, const SectionProgress& progress);  // reproduce_section_6_4.cpp
// Beyond the dissertation: uncertainty and robust design (issue 15), reproduce_section_uncertainty.cpp.
SectionReport section_uncertainty(const RunContext& context, const SectionProgress& progress);
// Beyond the dissertation: a needle array (issue 36), reproduce_section_arrays.cpp.
SectionReport section_arrays(const RunContext& context, const SectionProgress& progress);

// The input files a section needs (checked before the run starts, so that a missing file fails at once).
std::vector<std::filesystem::path> section_6_4_mesh_files(const RunContext& context);

}  // namespace needlekit::cli::reproduce
