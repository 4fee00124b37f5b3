// Curve files: see curve_io.h.
#include "io/file_bytes.h"
#include "io/curve_io.h"
#include <cmath>
#include <cstdlib>
#include "core/error.h"

namespace caustica {

std::vector<std::vector<glm::vec4>> parse_curves(const std::string& text, const std::string& name, size_t min_points) {
  std::vector<std::vector<glm::vec4>> curves;
  std::vector<size_t> first_line;  // of each curve, for messages
  bool open = false;
  auto close = [&] {
    if (open && curves.back().size() < min_points) {
      throw InputError(name + ":" + std::to_string(first_line.back()) + ": the curve starting here has " +
                       std::to_string(curves.back().size()) + " control point(s); it needs at least " +
                       std::to_string(min_points));
    }
    open = false;
  };
  size_t line_no = 0, at = 0;
  while (at <= text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_no;
    const char* p = line.c_str();
    while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
    if (*p == '\0') {
      close();
      if (end == text.size()) break;
      continue;
    }
    float v[4];
    for (int i = 0; i < 4; ++i) {
      char* next = nullptr;
      v[i] = std::strtof(p, &next);
      if (next == p) {
        throw InputError(name + ":" + std::to_string(line_no) + ": expected a control point \"x y z radius\" (four numbers)");
      }
      p = next;
    }
    while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
    if (*p != '\0') throw InputError(name + ":" + std::to_string(line_no) + ": more than four numbers on a control point's line");
    for (int i = 0; i < 4; ++i) {
      if (!std::isfinite(v[i])) throw InputError(name + ":" + std::to_string(line_no) + ": a control point value is not finite");
    }
    if (v[3] < 0.0f) throw InputError(name + ":" + std::to_string(line_no) + ": the radius is negative");
    if (!open) {
      curves.emplace_back();
      first_line.push_back(line_no);
      open = true;
    }
    curves.back().push_back(glm::vec4(v[0], v[1], v[2], v[3]));
    if (end == text.size()) break;
  }
  close();
  if (curves.empty()) throw InputError(name + ": no control points (an empty curve file)");
  return curves;
}

std::vector<std::vector<glm::vec4>> read_curve_file(const std::string& path, size_t min_points) {
  return parse_curves(read_file_bytes(path, "curve file"), path, min_points);
}

}  // namespace caustica
