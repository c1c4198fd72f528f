// Short text forms of medium parameters for `kiln info` (Medium describe()) and messages.
#pragma once
#include <cstdio>
#include <string>

#include "core/color.h"

namespace kiln {

inline std::string describe_rgb(Rgb c) {
  char buf[96];
  if (c.r == c.g && c.g == c.b)
    std::snprintf(buf, sizeof buf, "%g", double(c.r));
  else
    std::snprintf(buf, sizeof buf, "(%g %g %g)", double(c.r), double(c.g), double(c.b));
  return buf;
}

inline std::string quoted(const std::string& s) { return "\"" + s + "\""; }

inline std::string describe_float(float x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(x));
  return buf;
}

}  // namespace kiln
