// Implausible scales. A value far outside the range where it is plausible is most often a unit mistake: "400 mm"
// written for "400 um", a mesh in millimetres declared as metres. The check names the value, the plausible range and
// the value it would have with the unit off by a factor of 10, 100 or 1000 — the likely mistake — and is a warning,
// not an error (an unusual design may be meant): callers put it in their result's notes and on the terminal.
#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace needlekit::units {

// nullopt when `length` (m) lies in [low, high]; else e.g. "needle.length is 400 mm, outside the plausible 20 um to
// 5 mm: a unit mistake? with the unit 1000x smaller it would be 400 um".
std::optional<std::string> implausible_length(std::string_view what, double length, double low, double high);

// A length in a readable unit (nm, um, mm or m), 4 significant digits: "400 um", "8.5 m".
std::string readable_length(double length);

}  // namespace needlekit::units
