// The error for bad input of any kind (scene file, command line, image or mesh file): its
// message is for the user and names the file and the place in it.
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

namespace caustica {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(shorten(message)) {}
  explicit InputError(const char* message) : InputError(std::string(message)) {}

  // A message may quote what the user wrote, and that may be a megabyte of attribute value or
  // key name: a line longer than kMaxLine keeps its start and its end, and says how much it left
  // out between them.
  static constexpr size_t kMaxLine = 1000;
  static std::string shorten(const std::string& message) {
    std::string out;
    size_t start = 0;
    while (start <= message.size()) {
      size_t end = message.find('\n', start);
      if (end == std::string::npos) end = message.size();
      const size_t length = end - start;
      if (length <= kMaxLine) {
        out.append(message, start, length);
      } else {
        const size_t keep = kMaxLine / 2 - 50;
        out.append(message, start, keep);
        out += " [... " + std::to_string(length - 2 * keep) + " characters left out ...] ";
        out.append(message, end - keep, keep);
      }
      if (end == message.size()) break;
      out += '\n';
      start = end + 1;
    }
    return out;
  }
};

// A number as messages quote it: printf's %g ("2e+18", "0.5").
inline std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace caustica
