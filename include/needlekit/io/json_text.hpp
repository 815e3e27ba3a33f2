// The text of every JSON result needlekit writes or prints: numbers rounded to 12 significant digits, so that a value
// the user gave comes back as given after a unit conversion ("stiffness_N_per_mm2": 0.2, not 0.19999999999999998).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace needlekit::io {

// `value` with every floating-point number rounded to 12 significant digits (units::round_to_12_digits).
nlohmann::json rounded_numbers(nlohmann::json value);

// rounded_numbers(value), indented by 2, with a final newline.
std::string json_text(const nlohmann::json& value);

}  // namespace needlekit::io
