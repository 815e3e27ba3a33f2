// `needlekit uncertainty` beyond a design file: on a patch case (command_uncertainty_patch.cpp: parses, calls
// uncertainty::patch_uncertainty(), presents a table or JSON; with --out: JSON, CSV, VTU and a PNG map) and on an FE
// indentation case (command_uncertainty_fe.cpp: uncertainty::fe_surrogate(); with --out: JSON and the FE runs' CSV).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace needlekit::cli {

// The arguments of `needlekit uncertainty`, for every kind of UQ file.
struct UncertaintyArguments {
  std::string path;
  bool json = false;
  std::string out_dir;
  int threads = 0;
  bool no_plot = false;
};

void run_patch_uncertainty(const UncertaintyArguments& arguments);
void run_fe_uncertainty(const UncertaintyArguments& arguments);

// Shared by both tables (command_uncertainty.cpp): "N samples (method, seed S), E <runs>: status", the reason and
// the inputs; and the rows of json["probabilities"] under a header naming `what` ("event", "patch event").
void print_study_header(const nlohmann::json& json, std::string_view runs);
void print_probabilities(const nlohmann::json& json, std::string_view what);
// A JSON number in `format`, "-" for null.
std::string json_number(const nlohmann::json& value, std::string_view format = "{:.4g}");

// The placement keys a patch case adds to [uncertain], for the help.
std::string patch_inputs_help();
// The FE-case form of a UQ file, for the help.
std::string fe_help();

}  // namespace needlekit::cli
