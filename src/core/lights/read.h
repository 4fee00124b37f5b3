// What several light plugins read alike.
#pragma once
#include "core/params.h"

namespace caustica {

// A required colour that must not be black ("a light with zero intensity emits nothing").
inline Color read_nonzero(const Params& p, const std::string& key) {
  const Color c = p.color(key);
  if (is_black(c)) p.fail(key, "a light with zero " + key + " emits nothing");
  return c;
}

// A required direction, normalised; zero is an error.
inline Vec3 read_direction(const Params& p, const std::string& key) {
  const Vec3 d = scaled_to_unit_max(p.vec3(key));
  if (!(max_component(glm::abs(d)) > 0.0f)) p.fail(key, "direction must not be zero");
  return glm::normalize(d);
}

// Where a light at `position` points: `direction`, or `target` minus the position (one of the two).
inline Vec3 read_aim(const Params& p, const Vec3& position) {
  if (p.has("target") == p.has("direction")) p.fail("", "give either direction or target");
  if (!p.has("target")) return read_direction(p, "direction");
  const Vec3 dir = p.point("target") - position;
  if (!(glm::length(dir) > 0.0f)) p.fail("target", "target equals position");
  return dir;
}

}  // namespace caustica
