// Error metrics between an image and a reference, and false-colour error maps.
#pragma once
#include <string>
#include <vector>
#include "core/image.h"

namespace caustica {

struct ErrorMetrics {
  double rmse = 0;    // sqrt(mean((a - b)^2)) over pixels and channels
  double relmse = 0;  // mean((a - b)^2 / (b^2 + 0.01))
  double mae = 0;     // mean |a - b|
  double psnr = 0;    // 20 log10(1 / rmse), peak 1 (infinite for identical images)
  double max_error = 0;
  Color mean_image{0.0f}, mean_reference{0.0f};
};

// Throws InputError when the sizes differ (`image_name`, `reference_name` name them).
ErrorMetrics compare_images(const Image& image, const Image& reference, const std::string& image_name = "image",
                            const std::string& reference_name = "reference");

// A reference made of independent renders of one scene (other seeds): their mean, and the
// relMSE that mean itself carries against the converged image, estimated from the renders'
// spread. An image's relMSE against the mean is, in expectation, its relMSE against the
// converged image plus that floor (the noises are independent), so relmse - floor estimates
// the error against the truth. With one render the floor is unknown: 0, and `renders` says 1.
struct Reference {
  Image mean;
  double floor = 0;  // mean over pixels and channels of Var(mean) / (mean^2 + 0.01)
  size_t renders = 0;
  bool has_floor() const { return renders >= 2; }
};

// Throws InputError when the sizes differ (names[i] names renders[i]) or there is none.
Reference combine_references(const std::vector<Image>& renders, const std::vector<std::string>& names);

// Per-pixel relative squared error (averaged over channels) in false colour (a perceptual
// dark-blue-to-yellow ramp on a log scale from 1e-4 to 1), with a labelled colour bar below.
Image error_map(const Image& image, const Image& reference);

// The false-colour ramp used by error maps and heat maps: t in [0, 1].
Color false_colour(float t);

}  // namespace caustica
