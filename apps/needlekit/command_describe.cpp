// `needlekit describe KEY | --all [--markdown]`: a parameter's meaning, unit, default and range, from the parameter
// tables (reference/parameter_reference.hpp).
#include <fmt/format.h>

#include <memory>
#include <string>

#include "command_describe.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/reference/parameter_reference.hpp"

namespace needlekit::cli {
namespace {

struct DescribeArguments {
  std::string key;
  bool all = false;
  bool markdown = false;
};

void run_describe(const DescribeArguments& arguments) {
  if (arguments.markdown) {
    fmt::print("{}", reference::reference_markdown());
  } else if (arguments.all) {
    fmt::print("{}", reference::described_all());
  } else if (arguments.key.empty()) {
    throw InvalidInput("describe: expected a KEY (e.g. solver.friction) or --all");
  } else {
    fmt::print("{}", reference::described(arguments.key));
  }
}

}  // namespace

void add_describe_command(CLI::App& app) {
  auto arguments = std::make_shared<DescribeArguments>();
  CLI::App* command = app.add_subcommand(
      "describe", "Describe a parameter of the case files and the Python options: meaning, unit, default, range");
  command->add_option("KEY", arguments->key, "a dotted key, e.g. solver.friction");
  command->add_flag("--all", arguments->all, "every parameter");
  command->add_flag("--markdown", arguments->markdown, "every parameter as docs/reference.md holds them");
  command->callback([arguments] { run_describe(*arguments); });
}

}  // namespace needlekit::cli
