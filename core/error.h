// Errors for bad input. Every message names the file, the element or line, and what is wrong; the CLI maps
// kiln::Error to exit code 2.
#pragma once
#include <stdexcept>
#include <string>

namespace kiln {

inline constexpr int kExitBadInput = 2;

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  // "FILE:LOCATION: MESSAGE"; location is a line ("line 12") or an element path ("Mesh id=3 / Faces").
  Error(const std::string& file, const std::string& location, const std::string& message)
      : std::runtime_error(format(file, location, message)) {}

  static std::string format(const std::string& file, const std::string& location, const std::string& message) {
    std::string s = file;
    if (!location.empty()) s += (s.empty() ? "" : ": ") + location;
    if (!s.empty()) s += ": ";
    return s + message;
  }
};

}  // namespace kiln
