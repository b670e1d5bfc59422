// JSON text of the summary files (json_text.hpp).
#include "io/json_text.hpp"

#include <cmath>
#include <cstdio>

namespace mpm3d {

std::string json_escape(const std::string& s) {
  std::string r;
  for (char ch : s) {
    if (ch == '"' || ch == '\\') r += '\\', r += ch;
    else if (static_cast<unsigned char>(ch) < 32) r += ' ';
    else r += ch;
  }
  return r;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

}  // namespace mpm3d
