#include "needlekit/io/json_text.hpp"

#include "needlekit/core/units.hpp"

namespace needlekit::io {
namespace {

void round_in_place(nlohmann::json& value) {
  if (value.is_number_float()) {
    value = units::round_to_12_digits(value.get<double>());
  } else if (value.is_structured()) {
    for (nlohmann::json& item : value) round_in_place(item);
  }
}

}  // namespace

nlohmann::json rounded_numbers(nlohmann::json value) {
  round_in_place(value);
  return value;
}

std::string json_text(const nlohmann::json& value) { return rounded_numbers(value).dump(2) + "\n"; }

}  // namespace needlekit::io
