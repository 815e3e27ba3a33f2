// `needlekit reproduce [--quick] [--out DIR]`: the main job. Runs the examples of dissertation Chapter 6 (§6.2 forces,
// §6.3 performance index and optimizer, §6.4 patches), writes their data, figures and a self-contained report
// (DIR/report.html) that sets needlekit's numbers beside the published ones.
//
// Everything is written under DIR/.reproduce-staging-<pid> first and moved into DIR only when the run is complete
// (report.html last), so that a failure or Ctrl-C leaves no half-written report: an interrupted run removes its
// staging folder and exits with 130.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "commands.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/view_page.hpp"
#include "progress_bar.hpp"
#include "reproduce_report.hpp"
#include "reproduce_sections.hpp"
#include "viewer_sources.hpp"
#include "resources_root.hpp"

namespace needlekit::cli {
namespace {

namespace fs = std::filesystem;
using reproduce::RunContext;
using reproduce::SectionReport;

struct ReproduceArguments {
  bool quick = false;
  bool with_calibration = false;
  std::string out_dir = "out";
  std::string meshes_dir;
  std::string python;
};

// Creates DIR and the staging folder inside it; throws IoError naming DIR when it cannot be written.
fs::path create_staging(const fs::path& out) {
  std::error_code error;
  fs::create_directories(out, error);
  if (error || !fs::is_directory(out)) {
    throw IoError(fmt::format("cannot create the output directory '{}': {}", out.string(),
                              error ? error.message() : "it exists and is not a directory"));
  }
  const fs::path staging = out / fmt::format(".reproduce-staging-{}", ::getpid());
  fs::remove_all(staging, error);
  fs::create_directory(staging, error);
  if (error || ::access(staging.c_str(), W_OK) != 0) {
    throw IoError(fmt::format("cannot write to the output directory '{}': {}", out.string(),
                              error ? error.message() : "permission denied"));
  }
  return staging;
}

// Moves every file of the staging folder into `out`, replacing earlier results of the same name, report.html last;
// removes the staging folder.
void publish(const fs::path& staging, const fs::path& out) {
  std::vector<fs::path> entries;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging)) {
    if (entry.path().filename() != "report.html") entries.push_back(entry.path());
  }
  entries.push_back(staging / "report.html");
  for (const fs::path& entry : entries) {
    const fs::path target = out / entry.filename();
    std::error_code error;
    fs::remove_all(target, error);
    fs::rename(entry, target, error);
    if (error) throw IoError(fmt::format("cannot move {} to {}: {}", entry.string(), target.string(), error.message()));
  }
  fs::remove_all(staging);
}

// Runs `python script staging` and waits; SIGINT reaches the script too (same process group).
void run_report_script(const std::string& python, const fs::path& script, const fs::path& staging) {
  int exit_code = 0;
  try {
    exit_code = run_program({python, script.string(), staging.string()});
  } catch (const IoError&) {
    throw IoError(fmt::format("cannot run '{}' for the report figures (install python3 with matplotlib: "
                              "scripts/install-deps)",
                              python));
  }
  if (exit_code != 0) {
    throw std::runtime_error(fmt::format("the report script {} failed (exit code {}); the run's data were not "
                                         "published",
                                         script.string(), exit_code));
  }
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  return text;
}

// The 3D views' viewer (docs/views.md) in DIR/viewer when a section has a view: results["viewer"] names the folder,
// or results["viewer_error"] says why the views cannot be shown (the report says so instead of failing the run).
void add_viewer(const RunContext& context, nlohmann::json& results) {
  bool any = false;
  for (const nlohmann::json& section : results["sections"]) {
    any = any || !section.value("views", nlohmann::json::array()).empty();
  }
  if (!any) return;
  try {
    for (const auto& [name, content] : io::viewer_files(viewer_sources())) {
      context.write(fs::path(io::kViewerFolder) / name, content);
    }
    results["viewer"] = io::kViewerFolder;
  } catch (const IoError& error) {
    fmt::print(stderr, "needlekit: the report's 3D views are left out: {}\n", error.what());
    results["viewer_error"] = error.what();
  }
}

// One section with its progress bar and a summary line; a section that fails is reported as failed and the run
// goes on (the exit code says so at the end).
SectionReport run_section(const std::string& label,
                          SectionReport (*section)(const RunContext&, const reproduce::SectionProgress&),
                          const RunContext& context) {
  const auto start = std::chrono::steady_clock::now();
  ProgressBar bar(label);
  SectionReport report("", "");
  try {
    report = section(context, [&bar](double fraction, const std::string&) { bar.update(fraction); });
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& error) {
    throw_if_interrupted();
    report = SectionReport(label, label);
    report.failed(error.what());
  }
  bar.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.set_seconds(seconds);
  const nlohmann::json& json = report.json();
  int agree = 0, reproducing = 0, reproducing_agree = 0;
  for (const nlohmann::json& c : json["comparisons"]) {
    agree += c["agrees"].get<bool>();
    reproducing += c["reproduces"].get<bool>();
    reproducing_agree += c["reproduces"].get<bool>() && c["agrees"].get<bool>();
  }
  if (json["status"] == "ok") {
    fmt::print("{}: {} numbers beside the dissertation's, {} agree to the printed digits ({} of the {} that should); "
               "{} figures; {:.1f} s\n",
               label, json["comparisons"].size(), agree, reproducing_agree, reproducing, json["figures"].size(),
               seconds);
  } else {
    fmt::print("{}: {}{}\n", label, json["status"] == "failed" ? "FAILED: " : "", json["reason"].get<std::string>());
  }
  std::fflush(stdout);
  return report;
}

// The run's context: the published values and resources, the meshes of §6.4 (checked before anything runs) and the
// staging folder every file is written to first.
RunContext run_context(const ReproduceArguments& arguments, const reproduce::PublishedValues& published,
                       const fs::path& resources) {
  RunContext context;
  context.quick = arguments.quick;
  context.with_calibration = arguments.with_calibration;
  context.resources = resources;
  // The meshes of §6.4: those the patch examples name, or the files of the same names in --meshes.
  context.meshes = arguments.meshes_dir;
  context.published = &published;
  for (const fs::path& mesh : reproduce::section_6_4_mesh_files(context)) {
    if (!fs::is_regular_file(mesh)) {
      throw IoError(fmt::format("mesh file not found: {} (needed by §6.4; pass --meshes DIR, the folder with the "
                                "body surface meshes)",
                                mesh.string()));
    }
  }
  context.staging = create_staging(arguments.out_dir);
  return context;
}

// Every section in turn, then results.json (with the viewer) and the report script's report.html in the staging
// folder; returns the number of sections that failed.
int run_sections(const ReproduceArguments& arguments, RunContext& context, const fs::path& resources,
                 const std::string& started, std::chrono::steady_clock::time_point start) {
  std::vector<SectionReport> sections;
  sections.push_back(run_section("§6.2 insertion forces", reproduce::section_6_2, context));
  context.check_interrupt();
  sections.push_back(run_section("§6.3 performance index", reproduce::section_6_3, context));
  context.check_interrupt();
  sections.push_back(run_section("§6.4 patches", reproduce::section_6_4, context));
  context.check_interrupt();
  sections.push_back(run_section("uncertainty", reproduce::section_uncertainty, context));
  context.check_interrupt();
  sections.push_back(run_section("arrays", reproduce::section_arrays, context));
  context.check_interrupt();

  nlohmann::json results = {
      {"title", "Dissertation Chapter 6 reproduced by needlekit"},
      {"dissertation", "P. Boonma, Geometric Modeling and Analysis of Microneedle Interaction with Soft Tissue, "
                       "PhD dissertation, NC State University, 2012"},
      {"mode", arguments.quick ? "quick" : "full"},
      {"started_utc", started},
      {"command", arguments.quick ? "needlekit reproduce --quick" : "needlekit reproduce"},
      {"hardware_threads", std::thread::hardware_concurrency()},
      {"published_values", "docs/published/chapter6.json"},
      {"sections", nlohmann::json::array()}};
  int failed_sections = 0;
  for (const SectionReport& section : sections) {
    results["sections"].push_back(section.json());
    failed_sections += section.json()["status"] == "failed";
  }
  add_viewer(context, results);
  results["finished_utc"] = utc_now();
  results["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  context.write("results.json", io::json_text(results));

  ProgressBar bar("report (figures, report.html)");
  bar.update(0);
  const std::string python =
      !arguments.python.empty() ? arguments.python : (fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3");
  run_report_script(python, resources / "scripts" / "report.py", context.staging);
  bar.finish();
  return failed_sections;
}

void run_reproduce(const ReproduceArguments& arguments) {
  const auto start = std::chrono::steady_clock::now();
  const std::string started = utc_now();
  const fs::path resources = resources_root({"docs/published/chapter6.json", "scripts/report.py"});
  const reproduce::PublishedValues published =
      reproduce::PublishedValues::read(resources / "docs" / "published" / "chapter6.json");
  const fs::path out = arguments.out_dir;
  RunContext context = run_context(arguments, published, resources);
  int failed_sections = 0;
  try {
    fmt::print("needlekit reproduce ({} run): dissertation Chapter 6 -> {}\n", arguments.quick ? "quick" : "full",
               (out / "report.html").string());
    std::fflush(stdout);
    failed_sections = run_sections(arguments, context, resources, started, start);
    context.check_interrupt();
    publish(context.staging, out);
  } catch (const Interrupted&) {
    std::error_code ignored;
    fs::remove_all(context.staging, ignored);
    fmt::print(stderr, "\nneedlekit: the run was stopped: no report was written and its partial results were removed "
                       "({} is unchanged)\n",
               out.string());
    throw;
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(context.staging, ignored);
    throw;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("report: {} (self-contained; data and figures under {}/); {} run took {:.1f} s\n",
             (out / "report.html").string(), out.string(), arguments.quick ? "quick" : "full", seconds);
  if (failed_sections > 0) {  // the report and the other sections are kept: a failure with results, exit 3
    fmt::print(stderr, "needlekit: {} section(s) failed; the report says why\n", failed_sections);
    throw CommandOutcome{ExitCode::NumericalFailure};
  }
}

}  // namespace

void add_reproduce_command(CLI::App& app) {
  auto arguments = std::make_shared<ReproduceArguments>();
  CLI::App* command = app.add_subcommand(
      "reproduce",
      "The main job: runs the examples of dissertation Chapter 6 (§6.2 insertion forces, §6.3 performance index and "
      "optimizer, §6.4 patches on a neck and a skull) and writes DIR/report.html with needlekit's numbers and "
      "figures beside the published ones");
  command->add_flag("--quick", arguments->quick,
                    "coarser meshes and fewer sweep points (under 2 minutes; what the tests run)");
  command->add_flag("--with-calibration", arguments->with_calibration,
                    "also the §6.2 rows after calibration (E and P_c fitted on the sharp bevel, the blunt bevel and "
                    "the cylinder predicted: tens of FE runs, full run only)");
  command->add_option("--out", arguments->out_dir,
                      "output directory: report.html, results.json, data (CSV/JSON with units) and figures (PNG); "
                      "results of an earlier run with the same names are replaced when the run completes")
      ->type_name("DIR")
      ->capture_default_str();
  command->add_option("--meshes", arguments->meshes_dir,
                      "folder with the body surface meshes of §6.4 (default: the files named by examples/patch_*.toml)")
      ->type_name("DIR");
  command->add_option("--python", arguments->python,
                      "Python 3 with matplotlib that draws the figures (default: /usr/bin/python3)")
      ->type_name("EXE");
  command->footer(
      "Exit codes: 0 done; 2 bad input (output directory not writable, mesh file missing); 3 a section failed (the "
      "report is written and says why); 130 interrupted (Ctrl-C, SIGTERM: nothing is left behind).");
  command->callback([arguments] { run_reproduce(*arguments); });
}

}  // namespace needlekit::cli
