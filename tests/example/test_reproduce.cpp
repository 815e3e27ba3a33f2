// `needlekit reproduce --quick`, the main job, as a test: it writes a self-contained report with every figure, the
// numbers that the dissertation's formulas determine agree with the printed ones to their printed digits, and bad
// input (an output directory that cannot be written, a missing mesh, Ctrl-C) leaves no report behind.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include "../support/cli_run.hpp"
#include "../support/cli_signal.hpp"

using needlekit::test::CliRun;
using needlekit::test::file_text;
using needlekit::test::run_cli;
using testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) { return needlekit::test::fresh_directory("reproduce-" + name); }

// One unit of the last printed digit, computed here independently of the tool ("42.9" -> 0.1, "1.288e-4" -> 1e-7).
double last_digit(const std::string& printed) {
  const std::size_t e = printed.find_first_of("eE");
  const std::string mantissa = printed.substr(0, e);
  const int exponent = e == std::string::npos ? 0 : std::stoi(printed.substr(e + 1));
  const std::size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  return std::pow(10.0, exponent - decimals);
}

bool leaves_staging_behind(const fs::path& out) {
  if (!fs::exists(out)) return false;
  for (const auto& entry : fs::directory_iterator(out)) {
    if (entry.path().filename().string().rfind(".reproduce-staging", 0) == 0) return true;
  }
  return false;
}

// The quick run, once for the whole suite.
class Reproduce : public testing::Test {
protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_dir("quick"));
    run_ = new CliRun(run_cli(*dir_, "reproduce --quick --out out"));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete run_;
  }
  static nlohmann::json results() { return nlohmann::json::parse(file_text(*dir_ / "out" / "results.json")); }
  static void report_is_self_contained_with_every_figure();
  static void numbers_agree_to_the_printed_digits();
  static void table_6_3_shows_both_pitches();
  static void array_section_shows_the_bed_of_nails();

  static fs::path* dir_;
  static CliRun* run_;
};
fs::path* Reproduce::dir_ = nullptr;
CliRun* Reproduce::run_ = nullptr;

void Reproduce::report_is_self_contained_with_every_figure() {
  const fs::path out = *dir_ / "out";
  ASSERT_TRUE(fs::is_regular_file(out / "report.html"));
  EXPECT_FALSE(leaves_staging_behind(out));
  const std::string report = file_text(out / "report.html");
  const nlohmann::json r = results();
  EXPECT_EQ(r["mode"], "quick");
  EXPECT_GT(r["seconds"].get<double>(), 0);
  std::size_t figures = 0;
  for (const auto& section : r["sections"]) {
    for (const auto& figure : section["figures"]) {
      ++figures;
      const fs::path png = out / figure["file"].get<std::string>();
      ASSERT_TRUE(fs::is_regular_file(png)) << png;
      const std::string bytes = file_text(png);
      EXPECT_GT(bytes.size(), 5000u) << png << " is (nearly) empty";
      EXPECT_EQ(bytes.substr(1, 3), "PNG") << png;
    }
    for (const auto& data : section["data_files"]) {
      EXPECT_TRUE(fs::is_regular_file(out / data.get<std::string>())) << data;
    }
    // The 3D views (docs/views.md): each data file beside the report, within the 5 MB budget.
    for (const auto& view : section.value("views", nlohmann::json::array())) {
      const fs::path script = out / view["script"].get<std::string>();
      EXPECT_TRUE(fs::is_regular_file(script)) << script;
      if (fs::is_regular_file(script)) EXPECT_LE(fs::file_size(script), 5'000'000u) << script;
      EXPECT_THAT(report, HasSubstr("data-needlekit-view=\"" + view["name"].get<std::string>() + "\""));
    }
    // Every section is in the report, with its status.
    EXPECT_THAT(report, HasSubstr(section["title"].get<std::string>().substr(0, 10)));
  }
  EXPECT_GE(figures, 5u);
  // Self-contained: every figure embedded, nothing fetched from the network.
  std::size_t embedded = 0;
  for (std::size_t at = 0; (at = report.find("data:image/png;base64,", at)) != std::string::npos; ++at) ++embedded;
  EXPECT_EQ(embedded, figures);
  // The viewer is copied beside the report (three.js from libjs-three): the folder opens from file://.
  EXPECT_TRUE(fs::is_regular_file(out / "viewer" / "three.min.js"));
  EXPECT_TRUE(fs::is_regular_file(out / "viewer" / "needlekit_viewer.js"));
  EXPECT_THAT(report, testing::Not(HasSubstr("src=\"http")));
  EXPECT_THAT(report, testing::Not(HasSubstr("href=\"http")));
  EXPECT_THAT(run_->out, HasSubstr("report: "));
  EXPECT_THAT(run_->out, HasSubstr("quick run took"));
}

// §6.3.1, Figs 6.15/6.16, Table 6.3 (and the §6.4 forces, when that section runs): every number that the formulas
// determine is within one unit of its last printed digit, checked here against docs/published/chapter6.json.
void Reproduce::numbers_agree_to_the_printed_digits() {
  const nlohmann::json published =
      nlohmann::json::parse(file_text(fs::path(NEEDLEKIT_SOURCE_DIR) / "docs" / "published" / "chapter6.json"));
  std::map<std::string, nlohmann::json> by_id;
  for (const auto& v : published["values"]) by_id[v["id"]] = v;

  std::set<std::string> compared;
  std::set<std::string> sections_ok;
  const nlohmann::json run = results();
  for (const auto& section : run["sections"]) {
    if (section["status"] == "ok") sections_ok.insert(section["id"].get<std::string>());
    for (const auto& c : section["comparisons"]) {
      const std::string id = c["id"];
      ASSERT_TRUE(by_id.count(id)) << id;
      const nlohmann::json& p = by_id[id];
      compared.insert(id);
      EXPECT_EQ(c["published"], p["printed"]) << id;
      if (!p["reproduces"].get<bool>()) continue;
      const std::string printed = p["printed"];
      const double value = std::stod(printed);
      const double needlekit = c["needlekit"];
      if (value == 0) {
        EXPECT_EQ(needlekit, 0) << id;
      } else {
        EXPECT_LE(std::abs(needlekit - value), last_digit(printed) * (1 + 1e-9))
            << id << ": needlekit " << needlekit << ", printed " << printed;
      }
      EXPECT_TRUE(c["agrees"].get<bool>()) << id;
    }
  }
  ASSERT_TRUE(sections_ok.count("6.3"));
  // Every reproducible number of a section that ran is in the report (none silently dropped).
  for (const auto& [id, p] : by_id) {
    if (!p["reproduces"].get<bool>()) continue;
    for (const std::string section : {"6.3", "6.4"}) {
      if (id.rfind(section, 0) == 0 && sections_ok.count(section)) EXPECT_TRUE(compared.count(id)) << id;
    }
  }
  EXPECT_GE(compared.size(), 50u);
}

// Table 6.3 side by side: the corrected pitch finds better hollow cylinder and hollow cone designs than the
// published-compatible optimizer (which reproduces the printed rows).
void Reproduce::table_6_3_shows_both_pitches() {
  const nlohmann::json compat =
      nlohmann::json::parse(file_text(*dir_ / "out/section_6_3/table_6_3_hollow_cone_published_compat.json"));
  const nlohmann::json corrected =
      nlohmann::json::parse(file_text(*dir_ / "out/section_6_3/table_6_3_hollow_cone_corrected_pitch.json"));
  EXPECT_NEAR(compat["best"]["performance_index_per_um"].get<double>(), 0.00061, 0.00001);
  EXPECT_GT(corrected["best"]["performance_index_per_um"].get<double>(),
            1.5 * compat["best"]["performance_index_per_um"].get<double>());
}

// The array section (beyond the dissertation): every needle of the 3 x 3 patch in the table, all of them punctured
// by the end, and the closer the needles the further the plate travels to the first puncture.
void Reproduce::array_section_shows_the_bed_of_nails() {
  const nlohmann::json run = results();
  const nlohmann::json* arrays = nullptr;
  for (const auto& section : run["sections"]) {
    if (section["id"] == "arrays") arrays = &section;
  }
  ASSERT_NE(arrays, nullptr);
  ASSERT_EQ((*arrays)["status"], "ok") << (*arrays).value("reason", "");
  const nlohmann::json& needles = (*arrays)["tables"][0];
  ASSERT_EQ(needles["rows"].size(), 9u);
  for (const auto& row : needles["rows"]) EXPECT_GT(row[4].get<int>(), 0) << row;  // puncture_step
  const nlohmann::json& sweep = (*arrays)["tables"][1];
  ASSERT_EQ(sweep["columns"][1], "first_puncture_travel_um");
  double previous = 0;
  for (const auto& row : sweep["rows"]) {  // pitches from the widest to the closest
    ASSERT_TRUE(row[1].is_number()) << row;
    EXPECT_GE(row[1].get<double>(), previous) << row;
    previous = row[1].get<double>();
  }
  EXPECT_GT(previous, sweep["rows"][0][1].get<double>());
}

// One test for the whole quick run (CTest runs every test in its own process: one run, not one per check).
TEST_F(Reproduce, QuickRunWritesTheReportAndReproducesThePublishedNumbers) {
  ASSERT_EQ(run_->exit_code, 0) << run_->err;
  {
    SCOPED_TRACE("report and figures");
    report_is_self_contained_with_every_figure();
  }
  {
    SCOPED_TRACE("numbers that reproduce");
    numbers_agree_to_the_printed_digits();
  }
  {
    SCOPED_TRACE("Table 6.3");
    table_6_3_shows_both_pitches();
  }
  {
    SCOPED_TRACE("arrays");
    array_section_shows_the_bed_of_nails();
  }
}

TEST(ReproduceBadInput, UnwritableOutputDirectoryExitsWithCode2) {
  const fs::path dir = fresh_dir("unwritable");
  std::ofstream(dir / "a-file") << "not a directory\n";
  const CliRun run = run_cli(dir, "reproduce --quick --out a-file/out");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_THAT(run.err, HasSubstr("cannot create the output directory 'a-file/out'"));
  EXPECT_EQ(file_text(dir / "a-file"), "not a directory\n");
  fs::remove_all(dir);
}

TEST(ReproduceBadInput, MissingMeshFolderExitsWithCode2BeforeRunning) {
  const fs::path dir = fresh_dir("nomesh");
  const CliRun run = run_cli(dir, "reproduce --quick --out out --meshes no-such-folder");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_THAT(run.err, HasSubstr("no-such-folder"));
  EXPECT_FALSE(fs::exists(dir / "out" / "report.html"));
  EXPECT_FALSE(leaves_staging_behind(dir / "out"));
  fs::remove_all(dir);
}

// Ctrl-C (SIGINT to the whole process group, as a terminal sends it) mid-run: a clear message, exit code 130, no
// report and no staging folder left behind.
TEST(ReproduceBadInput, CtrlCLeavesNoHalfWrittenReport) {
  const fs::path dir = fresh_dir("sigint");
  // Interrupted once the run is under way (its staging folder exists).
  const CliRun run = needlekit::test::run_cli_and_signal(
      dir, {"reproduce", "--quick", "--out", "out"},
      [&] {
        if (!leaves_staging_behind(dir / "out")) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        return true;
      },
      SIGINT);
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_THAT(run.err, HasSubstr("interrupted"));
  EXPECT_FALSE(fs::exists(dir / "out" / "report.html"));
  EXPECT_FALSE(leaves_staging_behind(dir / "out"));
  fs::remove_all(dir);
}

}  // namespace
