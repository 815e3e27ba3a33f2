// needlekit command-line tool: parses the subcommand and turns library exceptions into messages and exit codes:
// needlekit::ExitCode (core/exit_codes.hpp): 0 success, 2 bad input (InvalidInput, IoError, command-line errors),
// 3 a numerical failure whose results were kept (a command throws cli::CommandOutcome after writing them),
// 130 interrupted (SIGINT/SIGTERM set needlekit's interrupt flag, core/interrupt.hpp; the command stops at its next
// check with needlekit::Interrupted, every file it wrote complete), 1 an unexpected internal error.
#include <fmt/format.h>

#include <cstdio>
#include <exception>

#include "blas_kernels.hpp"
#include "command_describe.hpp"
#include "commands.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/fem/parallel_session.hpp"

namespace {

using needlekit::ExitCode;

int code(ExitCode exit_code) { return static_cast<int>(exit_code); }

int report_error(std::string_view kind, std::string_view message, int exit_code) {
  fmt::print(stderr, "needlekit: {}: {}\n", kind, message);
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  needlekit::cli::use_avx2_blas_kernels(argc, argv);  // may re-execute the program, so before anything else
  // MPI under mpirun (before anything else that could run in parallel) and PETSc's -ksp_*/-pc_* options out of argv.
  needlekit::fem::ParallelSession parallel_session(argc, argv);
  if (needlekit::fem::process_rank() != 0) {  // every rank runs the same command: rank 0 alone prints
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
  }
  needlekit::install_interrupt_handlers();  // a signal from now on stops the command cleanly
  CLI::App app{"needlekit: design and analysis of microneedle arrays (P. Boonma, NC State 2012). Every dimensional "
               "input carries its unit (\"70 um\", \"169 GPa\").",
               "needlekit"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fmt::format("needlekit {} (FE linear-solve backends: {})", NEEDLEKIT_VERSION,
                                                needlekit::fem::compiled_backend_names()));
  needlekit::cli::add_evaluate_command(app);
  needlekit::cli::add_optimize_command(app);
  needlekit::cli::add_sweep_command(app);
  needlekit::cli::add_materials_command(app);
  needlekit::cli::add_mesh_command(app);
  needlekit::cli::add_tissue_mesh_command(app);
  needlekit::cli::add_surface_command(app);
  needlekit::cli::add_patch_command(app);
  needlekit::cli::add_reproduce_command(app);
  needlekit::cli::add_indent_command(app);
  needlekit::cli::add_insert_command(app);
  needlekit::cli::add_uncertainty_command(app);
  needlekit::cli::add_calibrate_command(app);
  needlekit::cli::add_serve_command(app);
  needlekit::cli::add_describe_command(app);
  app.footer("Run `needlekit COMMAND --help` for the options and input formats of a command.");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);  // --help
    return report_error("error", fmt::format("{} (see needlekit --help)", error.what()), code(ExitCode::InvalidInput));
  } catch (const needlekit::cli::CommandOutcome& outcome) {
    return code(outcome.exit_code);
  } catch (const needlekit::Interrupted&) {
    return report_error("interrupted", "stopped on request (SIGINT/SIGTERM); every file written is complete",
                        code(ExitCode::Interrupted));
  } catch (const needlekit::InvalidInput& error) {
    return report_error("error", error.what(), code(ExitCode::InvalidInput));
  } catch (const needlekit::IoError& error) {
    return report_error("error", error.what(), code(ExitCode::InvalidInput));
  } catch (const std::exception& error) {
    return report_error("internal error", error.what(), code(ExitCode::InternalError));
  }
  return code(ExitCode::Success);
}
