// Pixel reconstruction filters by importance sampling (as pbrt-v4 does): each camera sample lands
// at an offset from the pixel centre distributed like the filter, with weight 1, so the image is
// the radiance convolved with the filter. Box (the default), Gaussian and tent, all separable.
#pragma once
#include <string>
#include <vector>
#include "core/math.h"

namespace caustica {

class PixelFilter {
 public:
  static PixelFilter box();
  // Mitsuba's gaussian: standard deviation in pixels, cut off at 4 sigma.
  static PixelFilter gaussian(float stddev);
  // Mitsuba's tent: 1 - |x| / radius, radius in pixels.
  static PixelFilter tent(float radius);

  bool is_box() const { return cdf_.empty(); }
  const std::string& name() const { return name_; }
  float radius() const { return radius_; }
  // The offset from the pixel's centre for u in [0, 1)^2 (box: u - 0.5).
  Vec2 sample(const Vec2& u) const;

 private:
  float sample1(float u) const;
  std::string name_ = "box";
  float radius_ = 0.5f;
  std::vector<float> cdf_;  // over [-radius, radius] in equal steps; empty for the box
};

}  // namespace caustica
