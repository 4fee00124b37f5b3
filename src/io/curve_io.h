// Mitsuba's curve files (`linearcurve`, `bsplinecurve`): text, one control point per line as
// "x y z radius", a blank line between curves. Every way a file can be wrong is an error naming
// the file and the line: a line that is not four numbers, a position or radius that is not
// finite, a negative radius, a curve with fewer points than its degree needs, no points at all.
#pragma once
#include <string>
#include <vector>
#include "core/math.h"

namespace caustica {

// Control points (x, y, z, radius) of each curve; `min_points` per curve (2 for linear curves).
std::vector<std::vector<glm::vec4>> parse_curves(const std::string& text, const std::string& name, size_t min_points);
std::vector<std::vector<glm::vec4>> read_curve_file(const std::string& path, size_t min_points);

}  // namespace caustica
