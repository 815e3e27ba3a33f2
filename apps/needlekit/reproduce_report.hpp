// The report model of `needlekit reproduce`: the dissertation's published numbers (docs/published/chapter6.json), one
// section's results (inputs, needlekit's numbers beside the published ones, tables, figure specifications,
// deviations) as JSON, and the run context that every section writes its data files through.
//
// Agreement rule (used by the report and the tests): a needlekit value agrees with a printed value when they differ
// by at most one unit of the last printed digit ("42.9" -> 0.1, "1.288e-4" -> 1e-7); a printed 0 needs an exact 0.
// One unit covers both rounding and the truncation the text uses (42.98 um is printed 42.9).
#pragma once
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace needlekit::cli::reproduce {

// One published number as printed, with its unit and where it is printed.
struct PublishedValue {
  std::string id;
  std::string printed;      // e.g. "1.288e-4"
  double value = 0;         // the printed number
  double last_digit = 0;    // one unit of the last printed digit (0 for a printed 0)
  std::string unit;         // e.g. "um", "1/um", "N", "" (dimensionless)
  std::string where;        // e.g. "Table 6.3"
  bool reproduces = false;  // follows from the ch. 4-5 formulas to its printed digits (notes)
  std::string why_not;      // for reproduces == false: why not
};

// One unit of the last printed digit of a number printed as `printed` ("580" -> 1, "0.00061" -> 1e-5,
// "1.4093e-5" -> 1e-9, "0" -> 0).
double last_digit_unit(std::string_view printed);

class PublishedValues {
public:
  // Throws IoError for an unreadable or malformed file.
  static PublishedValues read(const std::filesystem::path& path);
  // Throws std::out_of_range naming the id when it is not in the file (a defect of the command, not of the input).
  const PublishedValue& at(const std::string& id) const;

private:
  std::map<std::string, PublishedValue> values_;
};

struct RunContext {
  bool quick = false;
  bool with_calibration = false;  // --with-calibration: the §6.2 rows after calibration (tens of FE runs)
  std::filesystem::path staging;    // every file of the run is written under this directory first
  std::filesystem::path resources;  // the needlekit tree: docs/published, examples, scripts
  std::filesystem::path meshes;     // --meshes: folder of the §6.4 body surface meshes (empty: as the examples say)
  const PublishedValues* published = nullptr;

  // Throws needlekit::Interrupted after Ctrl-C / SIGTERM (core/interrupt.hpp).
  void check_interrupt() const;
  // Writes `content` to staging/relative (creating folders); returns `relative` for the JSON.
  std::string write(const std::filesystem::path& relative, std::string_view content) const;
  std::filesystem::path example(std::string_view name) const { return resources / "examples" / name; }
};

// CSV text: one header line of `columns` and one line per row of `rows` (an array of arrays of numbers and strings;
// strings with a comma or a quote are quoted).
std::string csv_text(const std::vector<std::string>& columns, const nlohmann::json& rows);

// The results of one section of Chapter 6, as the report script reads them.
class SectionReport {
public:
  SectionReport(std::string id, std::string title);

  void input(std::string text);
  // needlekit's value beside a published one; `quantity` says what it is, `note` how needlekit's value was obtained
  // when that is not obvious.
  void compare(const PublishedValue& published, double needlekit, std::string quantity, std::string note = "");
  // A table: column names (with units) and rows of numbers or strings.
  void table(std::string title, std::vector<std::string> columns, nlohmann::json rows, std::string note = "");
  // A figure: `spec` holds the kind of plot and its data (inline or CSV files written by the run); `file` is the
  // PNG's path relative to the output directory.
  void figure(std::string file, std::string caption, nlohmann::json spec, std::string attribution = "");
  // A 3D view (docs/views.md) beside the figures: `script` is the view's data file (NAME_view.js) relative to the
  // output directory, `name` the view's "name", `caption` what it shows.
  void view(std::string script, std::string name, std::string caption);
  // A line on a difference from the dissertation and its cause.
  void deviation(std::string text);
  // The section could not run in this build (a capability is missing): the reason is shown in the report.
  void unavailable(std::string reason);
  // The section stopped with an error (a defect or a numerical failure): the reason is shown in the report.
  void failed(std::string reason);
  void data_file(std::string relative_path);
  void set_seconds(double seconds) { json_["seconds"] = seconds; }

  const nlohmann::json& json() const { return json_; }

private:
  nlohmann::json json_;
};

// Writes a 3D view (io/indentation_view.hpp, io/patch_view.hpp) as views/NAME_view.js, NAME unique in the report,
// and adds it to the section beside its figures.
void add_view(const RunContext& context, SectionReport& report, const std::string& name, nlohmann::json view,
              std::string caption);

}  // namespace needlekit::cli::reproduce
