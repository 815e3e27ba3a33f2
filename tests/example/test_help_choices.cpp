// The CLI help lists exactly the values the readers accept, for every enum-valued key of every input file: the
// choices printed by `needlekit COMMAND --help` (`key = "a" | "b"`), the names the reader accepts, and the names it
// lists when it rejects a value are the same set. A list written by hand in the help or the reader would drift
// (as the case reader's 3 of the solver's 5 boundary conditions once did) and fail here.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <functional>
#include <regex>
#include <set>
#include <string>

#include "needlekit/analysis/sensitivity_sweep.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/parameter_text.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/patch_config.hpp"

#include "../support/cli_run.hpp"

namespace {

using Names = std::set<std::string>;

// "a" | "b" | "c" -> {a, b, c}
Names quoted_names(const std::string& text) {
  Names names;
  const std::regex quoted("\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), quoted); it != std::sregex_iterator(); ++it)
    names.insert((*it)[1]);
  return names;
}

// The choices the help shows for `key`: the text `key = "a" | "b" ...`.
Names help_choices(const std::string& help, const std::string& key) {
  const std::regex choice("(^|[^a-z_])" + key + R"( = ((?:"[^"]+"(?: \| )?)+))");
  std::smatch match;
  if (!std::regex_search(help, match, choice)) {
    ADD_FAILURE() << "the help does not list the choices of " << key;
    return {};
  }
  return quoted_names(match[2]);
}

struct Probe {
  std::string key;                                        // as the help shows it
  std::function<void(const std::string& value)> read;  // reads a file with key = "value"; throws if rejected
};

// For each probed key: every name of the help is accepted, and a rejected name's message lists exactly the help's.
void expect_help_matches_reader(const std::string& command, const std::vector<Probe>& probes) {
  const needlekit::test::CliRun help = needlekit::test::run_cli(needlekit::test::fresh_directory("help-" + command),
                                                                command + " --help");
  ASSERT_EQ(help.exit_code, 0) << help.err;
  for (const Probe& probe : probes) {
    SCOPED_TRACE(command + ": " + probe.key);
    const Names listed = help_choices(help.out, probe.key);
    EXPECT_GE(listed.size(), 2u);
    for (const std::string& name : listed) EXPECT_NO_THROW(probe.read(name)) << name;
    try {
      probe.read("no-such-choice");
      ADD_FAILURE() << "accepted an unknown value";
    } catch (const needlekit::InvalidInput& error) {
      const std::string message = error.what();
      const std::size_t at = message.find("expected one of: ");
      ASSERT_NE(at, std::string::npos) << message;
      EXPECT_EQ(quoted_names(message.substr(at)), listed) << message;
    }
  }
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// An indentation case with one key set, on the ν = 0.4 skin: every linear solver is valid there (two-grid refuses
// the nodal average of a ν >= 0.45 layer).
Probe indentation_probe(const std::string& section, const std::string& key) {
  return {key, [section, key](const std::string& value) {
            std::string text = "[needle]\nshape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"1 mm\"\n"
                               "[tissue]\npreset = \"skin\"\n[loading]\n"
                               "depth = \"10 um\"\n";
            text += "[" + section + "]\n" + key + " = \"" + value + "\"\n";
            needlekit::io::parse_indentation_case_toml(text, "case.toml");
          }};
}

Probe design_probe(const std::string& key) {
  return {key, [key](const std::string& value) {
            std::string text = "[needle]\nshape = \"cone\"\ntip_diameter = \"30 um\"\nbase_diameter = \"150 um\"\n"
                               "length = \"500 um\"\nmaterial = \"silicon\"\n[array]\nneedles_per_row = 10\n"
                               "width = \"1 cm\"\n[insertion]\ntarget_depth = \"50 um\"\n";
            // effective_length applies to uniform columns only: probed on a cylinder.
            const std::string shape = key == "shape" ? value : key == "effective_length" ? "cylinder" : "cone";
            if (shape == "cylinder") text = replace_all(text, "base_diameter = \"150 um\"\n", "");
            text = replace_all(text, "shape = \"cone\"", "shape = \"" + shape + "\"");
            if (key != "shape") text += key + " = \"" + value + "\"\n";
            needlekit::io::parse_design_toml(text, "design.toml");
          }};
}

Probe patch_probe(const std::string& section, const std::string& key) {
  return {key, [section, key](const std::string& value) {
            std::string text =
                "[surface]\nmesh = \"neck.obj\"\nunit = \"m\"\ncenter_vertex = 0\n[patch]\nkind = \"flexible\"\n"
                "size = \"10 mm\"\nneedles_per_row = 10\nspring_constant = \"1 N/mm\"\nmax_spring_energy = \"0.05 mJ\"\n"
                "[needle]\nshape = \"cylinder\"\ntip_diameter = \"70 um\"\nlength = \"400 um\"\nmaterial = \"su-8\"\n";
            if (key == "kind" && value != "flexible") text = replace_all(text, "max_spring_energy = \"0.05 mJ\"\n", "");
            if (key == "kind") text = replace_all(text, "kind = \"flexible\"", "kind = \"" + value + "\"");
            else text = replace_all(text, "[" + section + "]\n", "[" + section + "]\n" + key + " = \"" + value + "\"\n");
            needlekit::io::parse_patch_case_toml(text, "patch.toml", ".");
          }};
}

TEST(HelpChoices, IndentHelpListsExactlyWhatTheCaseReaderAccepts) {
  expect_help_matches_reader("indent", {indentation_probe("model", "law"), indentation_probe("model", "contact"),
                                        indentation_probe("model", "element"), indentation_probe("model", "boundary"),
                                        indentation_probe("solver", "predictor"),
                                        indentation_probe("solver", "linear_solver")});
}

// The [solver] settings: the help shows each row of fem::kSolverParameters that is not a choice with its default
// (SolverOptions' initializer) and its range, and lists the names of each choice.
TEST(HelpChoices, IndentHelpShowsEachSolverSettingWithItsDefaultAndRange) {
  const needlekit::test::CliRun help =
      needlekit::test::run_cli(needlekit::test::fresh_directory("help-solver"), "indent --help");
  ASSERT_EQ(help.exit_code, 0) << help.err;
  for (const needlekit::ParameterText& parameter :
       needlekit::parameter_texts(needlekit::fem::kSolverParameters, needlekit::io::case_solver_defaults())) {
    SCOPED_TRACE(parameter.key);
    const std::string key = parameter.key.substr(parameter.key.find('.') + 1);
    if (parameter.kind == "choice") {
      EXPECT_THAT(help.out, testing::HasSubstr(parameter.choices));
    } else {
      EXPECT_THAT(help.out, testing::HasSubstr(fmt::format("{} = {}", key, parameter.default_text)));
      EXPECT_THAT(help.out, testing::HasSubstr(parameter.range + ": " + parameter.meaning));
    }
  }
}

TEST(HelpChoices, DesignHelpListsExactlyWhatTheDesignReaderAccepts) {
  for (const std::string command : {"evaluate", "sweep", "mesh"}) {
    expect_help_matches_reader(command, {design_probe("shape"), design_probe("end_condition"),
                                         design_probe("effective_length")});
  }
}

TEST(HelpChoices, SweepHelpListsExactlyTheParametersThatCanVary) {
  expect_help_matches_reader(
      "sweep", {{"PARAM", [](const std::string& value) { needlekit::analysis::sweep_parameter_from_string(value); }}});
}

TEST(HelpChoices, PatchHelpListsExactlyWhatThePatchReaderAccepts) {
  expect_help_matches_reader("patch", {patch_probe("surface", "approach"), patch_probe("patch", "kind"),
                                       patch_probe("patch", "first_node"), patch_probe("patch", "walk")});
}

}  // namespace
