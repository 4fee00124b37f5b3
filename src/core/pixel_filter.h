// Pixel reconstruction filters by importance sampling (as pbrt-v4 does): each camera sample lands
// at an offset from the pixel centre distributed like the filter, with weight 1, so the image is
// the radiance convolved with the filter. Box (the default), Gaussian and tent, all separable.
// Filters with negative lobes (Mitchell-Netravali, Catmull-Rom, Lanczos) are sampled in
// proportion to |f|; each sample then carries the weight sign(f) * (integral of |f|) /
// (integral of f) per axis, whose mean is 1, so the image is still the normalised convolution.
#pragma once
#include <cstdint>
#include <functional>
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
  // Mitsuba's mitchell: the Mitchell-Netravali cubic of parameters B and C, radius 2 pixels
  // (catmullrom is B = 0, C = 0.5).
  static PixelFilter mitchell(float b, float c, const std::string& name = "mitchell");
  // Mitsuba's lanczos: sinc(x) sinc(x / lobes) over |x| < lobes pixels.
  static PixelFilter lanczos(int lobes);
  // The filter's 1D profile at x pixels from the centre (unnormalised; box: 1 within 0.5).
  double profile(double x) const;

  bool is_box() const { return cdf_.empty(); }
  const std::string& name() const { return name_; }
  float radius() const { return radius_; }
  // The offset from the pixel's centre for u in [0, 1)^2 (box: u - 0.5), and through `weight`
  // the sample's weight (1 unless the filter has negative lobes).
  Vec2 sample(const Vec2& u, float* weight = nullptr) const;
  bool has_negative_lobes() const { return norm_ != 1.0f; }

 private:
  static PixelFilter tabulated(const std::string& name, float radius, std::function<double(double)> profile);
  float sample1(float u, float& sign) const;
  std::string name_ = "box";
  float radius_ = 0.5f;
  std::function<double(double)> profile_;  // empty for the box
  std::vector<float> cdf_;      // of |profile| over [-radius, radius] in equal bins; empty for the box
  std::vector<uint8_t> negative_;  // per bin: the profile is negative there
  float norm_ = 1.0f;           // (integral of |profile|) / (integral of profile), per axis
};

}  // namespace caustica
