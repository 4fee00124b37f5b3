// Error metrics on images with known error.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "io/json_reader.h"
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

TEST_CASE("metrics: a constant offset gives RMSE and MAE equal to the offset", "[core][metrics]" TIER_UNIT) {
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

TEST_CASE("metrics: identical images have zero error and infinite PSNR", "[core][metrics]" TIER_UNIT) {
  const Image ref = ramp(5, 5);
  const ErrorMetrics m = compare_images(ref, ref);
  CHECK(m.rmse == 0.0);
  CHECK(m.relmse == 0.0);
  CHECK(std::isinf(m.psnr));
}

TEST_CASE("metrics: a single wrong pixel", "[core][metrics]" TIER_UNIT) {
  Image ref(10, 10), img(10, 10);
  img.at(3, 4) = Color(1.0f, 0.0f, 0.0f);  // one channel of one pixel off by 1
  const ErrorMetrics m = compare_images(img, ref);
  CHECK(m.rmse == Approx(std::sqrt(1.0 / 300.0)).epsilon(1e-6));
  CHECK(m.relmse == Approx(1.0 / 0.01 / 300.0).epsilon(1e-6));
  CHECK(m.max_error == Approx(1.0));
}

TEST_CASE("metrics: different sizes are an error naming both", "[core][metrics]" TIER_UNIT) {
  REQUIRE_THROWS_WITH(compare_images(Image(4, 4), Image(4, 5), "a.exr", "b.exr"),
                      Catch::Contains("a.exr is 4x4, b.exr is 4x5"));
}

TEST_CASE("metrics: the error map has the image above a colour bar", "[core][metrics]" TIER_UNIT) {
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

TEST_CASE("metrics: several references give their mean and the relMSE their noise adds", "[core][metrics]" TIER_UNIT) {
  // A known image t, K = 4 references and one image, each t plus its own independent uniform
  // noise on [-a, a] (variance a^2 / 3). Against the references' mean, the image's relMSE is
  // its error against t plus the mean's own, a^2 / 3 / K per value: the floor.
  const int w = 256, h = 256, K = 4;
  const float a = 0.1f;
  Image truth(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) truth.at(x, y) = Color(0.5f + x / 256.0f, 1.0f + y / 256.0f, 0.8f);
  Rng rng(42);
  auto noisy = [&] {
    Image img = truth;
    for (Color& c : img.pixels)
      for (int k = 0; k < 3; ++k) c[k] += a * (2.0f * rng.next_float() - 1.0f);
    return img;
  };
  std::vector<Image> renders;
  for (int k = 0; k < K; ++k) renders.push_back(noisy());
  const Image image = noisy();
  const Reference ref = combine_references(renders, {"r0.exr", "r1.exr", "r2.exr", "r3.exr"});
  REQUIRE(ref.renders == size_t(K));
  REQUIRE(ref.mean.width == w);
  for (size_t i : {size_t(0), size_t(777), size_t(w * h - 1)}) {
    for (int c = 0; c < 3; ++c) {
      double sum = 0;
      for (const Image& r : renders) sum += r.pixels[i][c];
      CHECK(ref.mean.pixels[i][c] == Approx(sum / K).epsilon(1e-6));
    }
  }
  double expected_floor = 0, true_error = 0;
  for (size_t i = 0; i < truth.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double t = truth.pixels[i][c];
      expected_floor += double(a) * a / 3.0 / K / (t * t + 0.01);
      const double d = double(image.pixels[i][c]) - t;
      true_error += d * d / (t * t + 0.01);
    }
  }
  expected_floor /= 3.0 * truth.pixels.size();
  true_error /= 3.0 * truth.pixels.size();
  CHECK(ref.floor == Approx(expected_floor).epsilon(0.02));
  const ErrorMetrics m = compare_images(image, ref.mean);
  // The raw figure is a quarter too high (1 + 1/K); with the floor taken out it is the error
  // against the truth.
  CHECK(m.relmse == Approx(true_error * (1.0 + 1.0 / K)).epsilon(0.02));
  CHECK(m.relmse - ref.floor == Approx(true_error).epsilon(0.02));
  CHECK(compare_images(image, truth).relmse == Approx(true_error).epsilon(1e-6));
}

TEST_CASE("metrics: one reference has no floor; references of other sizes are an error", "[core][metrics]" TIER_UNIT) {
  const Image r = ramp(16, 8);
  const Reference one = combine_references({r}, {"r.exr"});
  CHECK(one.renders == 1);
  CHECK(one.floor == 0.0);
  CHECK(one.mean.pixels == r.pixels);
  try {
    combine_references({r, ramp(8, 8)}, {"a.exr", "b.exr"});
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == "reference sizes differ: b.exr is 8x8, a.exr is 16x8");
  }
  CHECK_THROWS_AS(combine_references({}, {}), InputError);
}
