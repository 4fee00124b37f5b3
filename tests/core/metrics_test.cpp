// Error metrics on images with known error.
#include <catch2/catch.hpp>
#include "core/json_reader.h"
#include "core/metrics.h"
#include "core/rng.h"

using namespace caustica;

namespace {
Image ramp(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y) = Color(0.1f * x, 0.05f * y, 0.5f);
  return img;
}
}  // namespace

TEST_CASE("metrics: a constant offset gives RMSE and MAE equal to the offset", "[core][metrics]") {
  const Image ref = ramp(16, 8);
  Image img = ref;
  for (Color& c : img.pixels) c += Color(0.25f);
  const ErrorMetrics m = compare_images(img, ref);
  CHECK(m.rmse == Approx(0.25).epsilon(1e-6));
  CHECK(m.mae == Approx(0.25).epsilon(1e-6));
  CHECK(m.psnr == Approx(20 * std::log10(1 / 0.25)).epsilon(1e-6));
  // relMSE = mean over pixels and channels of 0.0625 / (ref^2 + 0.01), computed directly.
  double rel = 0;
  for (const Color& c : ref.pixels)
    for (int k = 0; k < 3; ++k) rel += 0.0625 / (double(c[k]) * c[k] + 0.01);
  CHECK(m.relmse == Approx(rel / (3.0 * ref.pixels.size())).epsilon(1e-6));
  CHECK(m.mean_image.b == Approx(0.75f));
  CHECK(m.mean_reference.b == Approx(0.5f));
}

TEST_CASE("metrics: identical images have zero error and infinite PSNR", "[core][metrics]") {
  const Image ref = ramp(5, 5);
  const ErrorMetrics m = compare_images(ref, ref);
  CHECK(m.rmse == 0.0);
  CHECK(m.relmse == 0.0);
  CHECK(std::isinf(m.psnr));
}

TEST_CASE("metrics: a single wrong pixel", "[core][metrics]") {
  Image ref(10, 10), img(10, 10);
  img.at(3, 4) = Color(1.0f, 0.0f, 0.0f);  // one channel of one pixel off by 1
  const ErrorMetrics m = compare_images(img, ref);
  CHECK(m.rmse == Approx(std::sqrt(1.0 / 300.0)).epsilon(1e-6));
  CHECK(m.relmse == Approx(1.0 / 0.01 / 300.0).epsilon(1e-6));
  CHECK(m.max_error == Approx(1.0));
}

TEST_CASE("metrics: different sizes are an error naming both", "[core][metrics]") {
  REQUIRE_THROWS_WITH(compare_images(Image(4, 4), Image(4, 5), "a.exr", "b.exr"),
                      Catch::Contains("a.exr is 4x4, b.exr is 4x5"));
}

TEST_CASE("metrics: the error map has the image above a colour bar", "[core][metrics]") {
  const Image ref = ramp(64, 48);
  Image img = ref;
  img.at(10, 10) += Color(5.0f);
  const Image map = error_map(img, ref);
  CHECK(map.width == 64);
  CHECK(map.height > 48);
  // The wrong pixel is at the top of the ramp (yellow), an exact one at the bottom (dark).
  CHECK(map.at(10, 10).g > 0.5f);
  CHECK(map.at(20, 20).g < 0.05f);
  CHECK(false_colour(1.0f).g > false_colour(0.0f).g);  // the ramp rises
}
