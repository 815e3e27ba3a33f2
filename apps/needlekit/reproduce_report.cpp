#include "reproduce_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <fstream>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/view_page.hpp"

namespace needlekit::cli::reproduce {

double last_digit_unit(std::string_view printed) {
  const std::size_t e = printed.find_first_of("eE");
  const std::string_view mantissa = printed.substr(0, e);
  const int exponent = e == std::string_view::npos ? 0 : std::stoi(std::string(printed.substr(e + 1)));
  if (std::stod(std::string(mantissa)) == 0) return 0;
  const std::size_t dot = mantissa.find('.');
  const int decimals = dot == std::string_view::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  return std::pow(10.0, exponent - decimals);
}

PublishedValues PublishedValues::read(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError(fmt::format("{}: cannot read the published values of Chapter 6", path.string()));
  PublishedValues result;
  try {
    const nlohmann::json data = nlohmann::json::parse(in);
    for (const nlohmann::json& v : data.at("values")) {
      PublishedValue value;
      value.id = v.at("id").get<std::string>();
      value.printed = v.at("printed").get<std::string>();
      value.value = std::stod(value.printed);
      value.last_digit = last_digit_unit(value.printed);
      value.unit = v.at("unit").get<std::string>();
      value.where = v.at("where").get<std::string>();
      value.reproduces = v.at("reproduces").get<bool>();
      value.why_not = v.value("why_not", "");
      result.values_[value.id] = value;
    }
  } catch (const std::exception& error) {
    throw IoError(fmt::format("{}: malformed published values: {}", path.string(), error.what()));
  }
  return result;
}

const PublishedValue& PublishedValues::at(const std::string& id) const {
  const auto found = values_.find(id);
  if (found == values_.end()) throw std::out_of_range("published value '" + id + "' is not in chapter6.json");
  return found->second;
}

void RunContext::check_interrupt() const {
  throw_if_interrupted();
}

std::string RunContext::write(const std::filesystem::path& relative, std::string_view content) const {
  const std::filesystem::path path = staging / relative;
  std::error_code error;
  std::filesystem::create_directories(path.parent_path(), error);
  if (error) throw IoError(fmt::format("{}: cannot create the folder: {}", path.parent_path().string(), error.message()));
  io::write_text_file_atomically(path, content);
  return relative.generic_string();
}

std::string csv_text(const std::vector<std::string>& columns, const nlohmann::json& rows) {
  auto cell_text = [](const nlohmann::json& cell) {
    if (!cell.is_string()) return cell.is_null() ? std::string() : io::rounded_numbers(cell).dump();
    std::string text = cell.get<std::string>();
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return quoted + "\"";
  };
  std::string csv = fmt::format("{}\n", fmt::join(columns, ","));
  for (const nlohmann::json& row : rows) {
    std::vector<std::string> cells;
    for (const nlohmann::json& cell : row) cells.push_back(cell_text(cell));
    csv += fmt::format("{}\n", fmt::join(cells, ","));
  }
  return csv;
}

SectionReport::SectionReport(std::string id, std::string title) {
  json_ = {{"id", std::move(id)},      {"title", std::move(title)}, {"status", "ok"},      {"reason", ""},
           {"inputs", nlohmann::json::array()},  {"comparisons", nlohmann::json::array()},
           {"tables", nlohmann::json::array()},  {"figures", nlohmann::json::array()},
           {"views", nlohmann::json::array()},   {"deviations", nlohmann::json::array()},
           {"data_files", nlohmann::json::array()}, {"seconds", 0.0}};
}

void SectionReport::input(std::string text) { json_["inputs"].push_back(std::move(text)); }

void SectionReport::compare(const PublishedValue& published, double needlekit, std::string quantity,
                            std::string note) {
  const double difference = needlekit - published.value;
  const bool agrees = published.last_digit == 0 ? needlekit == 0
                                                : std::abs(difference) <= published.last_digit * (1 + 1e-9);
  nlohmann::json c = {{"id", published.id},
                      {"quantity", std::move(quantity)},
                      {"where", published.where},
                      {"unit", published.unit},
                      {"published", published.printed},
                      {"published_value", published.value},
                      {"last_digit", published.last_digit},
                      {"needlekit", needlekit},
                      {"difference", difference},
                      {"relative_difference",
                       published.value != 0 ? nlohmann::json(difference / published.value) : nlohmann::json()},
                      {"agrees", agrees},
                      {"reproduces", published.reproduces},
                      {"why_not", published.why_not},
                      {"note", std::move(note)}};
  json_["comparisons"].push_back(std::move(c));
}

void SectionReport::table(std::string title, std::vector<std::string> columns, nlohmann::json rows,
                          std::string note) {
  json_["tables"].push_back(
      {{"title", std::move(title)}, {"columns", std::move(columns)}, {"rows", std::move(rows)}, {"note", std::move(note)}});
}

void SectionReport::figure(std::string file, std::string caption, nlohmann::json spec, std::string attribution) {
  json_["figures"].push_back({{"file", std::move(file)},
                              {"caption", std::move(caption)},
                              {"spec", std::move(spec)},
                              {"attribution", std::move(attribution)}});
}

void SectionReport::view(std::string script, std::string name, std::string caption) {
  json_["views"].push_back({{"script", std::move(script)}, {"name", std::move(name)}, {"caption", std::move(caption)}});
}

void add_view(const RunContext& context, SectionReport& report, const std::string& name, nlohmann::json view,
              std::string caption) {
  if (view.value("steps", nlohmann::json::array()).empty()) return;  // a run without a converged step
  view["name"] = name;
  report.view(context.write(fmt::format("views/{}_view.js", name), io::view_script(view)), name, std::move(caption));
}

void SectionReport::deviation(std::string text) { json_["deviations"].push_back(std::move(text)); }

void SectionReport::unavailable(std::string reason) {
  json_["status"] = "not_available";
  json_["reason"] = std::move(reason);
}

void SectionReport::failed(std::string reason) {
  json_["status"] = "failed";
  json_["reason"] = std::move(reason);
}

void SectionReport::data_file(std::string relative_path) { json_["data_files"].push_back(std::move(relative_path)); }

}  // namespace needlekit::cli::reproduce
