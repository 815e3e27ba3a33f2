// The subcommands of the needlekit tool, one file each. Each adds itself to the application with its options and
// help text; its callback runs the command and throws needlekit::InvalidInput / IoError on bad input.
#pragma once
#include <CLI/CLI.hpp>

#include "needlekit/core/exit_codes.hpp"

namespace needlekit::cli {

// Thrown by a command's callback after it has printed and written everything it kept, to end the process with a
// non-zero code other than bad input (a numerical failure: 3; interrupted: 130). main() returns exit_code.
struct CommandOutcome {
  ExitCode exit_code;
};

void add_evaluate_command(CLI::App& app);   // command_evaluate.cpp
void add_optimize_command(CLI::App& app);   // command_optimize.cpp
void add_sweep_command(CLI::App& app);      // command_sweep.cpp
void add_materials_command(CLI::App& app);  // command_materials.cpp
void add_mesh_command(CLI::App& app);       // command_mesh.cpp
void add_tissue_mesh_command(CLI::App& app);  // command_tissue_mesh.cpp
void add_surface_command(CLI::App& app);    // command_surface.cpp
void add_patch_command(CLI::App& app);      // command_patch.cpp
void add_reproduce_command(CLI::App& app);  // command_reproduce.cpp
void add_indent_command(CLI::App& app);     // command_indent.cpp
void add_insert_command(CLI::App& app);     // command_insert.cpp
void add_uncertainty_command(CLI::App& app);  // command_uncertainty.cpp
void add_calibrate_command(CLI::App& app);  // command_calibrate.cpp
void add_serve_command(CLI::App& app);      // command_serve.cpp

}  // namespace needlekit::cli
