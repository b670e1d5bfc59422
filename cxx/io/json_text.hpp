// JSON text of the summary files: a string's content (quotes and backslashes escaped,
// control characters as spaces) and a number (shortest round-trip form, null when not
// finite). Shared by the program (app/cli.cpp) and the verification driver.
#pragma once
#include <string>

namespace mpm3d {

std::string json_escape(const std::string& s);
std::string json_number(double v);

}  // namespace mpm3d
