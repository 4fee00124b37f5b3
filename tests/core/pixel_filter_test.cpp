// Pixel filters: samples distributed as the filter (moments and a quantile), and Mitsuba's rfilter.
#include <catch2/catch.hpp>
#include "io/mitsuba/translate.h"
#include "core/pixel_filter.h"

using namespace caustica;

namespace {
struct Moments {
  double mean = 0, var = 0, max_abs = 0, inside_half = 0;
};
// Stratified u over [0, 1): the sample offsets' mean, variance, largest |x| and P(|x| < 0.5).
Moments moments(const PixelFilter& f) {
  constexpr int n = 200000;
  Moments m;
  for (int i = 0; i < n; ++i) {
    const float u = (float(i) + 0.5f) / n;
    const double x = f.sample(Vec2(u, 0.5f)).x;
    m.mean += x;
    m.var += x * x;
    m.max_abs = std::max(m.max_abs, std::abs(x));
    m.inside_half += std::abs(x) < 0.5;
  }
  m.mean /= n;
  m.var = m.var / n - m.mean * m.mean;
  m.inside_half /= n;
  return m;
}
}  // namespace

TEST_CASE("pixel filter: box, Gaussian and tent samples follow the filter", "[filter]") {
  const PixelFilter box = PixelFilter::box();
  CHECK(box.is_box());
  CHECK(box.sample(Vec2(0.25f, 0.75f)) == Vec2(-0.25f, 0.25f));

  const Moments g = moments(PixelFilter::gaussian(0.5f));
  CHECK(std::abs(g.mean) < 1e-4);
  // Cut off at 4 sigma, the variance is 0.99966 sigma^2.
  CHECK(g.var == Approx(0.25 * 0.99966).epsilon(0.005));
  CHECK(g.max_abs <= 2.0);
  CHECK(g.inside_half == Approx(0.6827).epsilon(0.005));  // P(|x| < sigma)

  const Moments t = moments(PixelFilter::tent(1.0f));
  CHECK(std::abs(t.mean) < 1e-4);
  CHECK(t.var == Approx(1.0 / 6.0).epsilon(0.005));
  CHECK(t.max_abs <= 1.0);
  CHECK(t.inside_half == Approx(0.75).epsilon(0.005));  // 1 - (1 - 0.5)^2
}

TEST_CASE("pixel filter: Mitsuba's rfilter and its default", "[filter][mitsuba]") {
  auto film = [](const std::string& inner) {
    return read_mitsuba("<scene version=\"3.0.0\"><sensor type=\"perspective\"><film type=\"hdrfilm\">" + inner +
                            "</film></sensor></scene>",
                        "s.xml", ".", {});
  };
  // No rfilter: Mitsuba's default Gaussian.
  CHECK(film("").doc["render"]["filter"] == nlohmann::json({{"type", "gaussian"}, {"stddev", 0.5}}));
  CHECK(film("<rfilter type=\"box\"/>").doc["render"]["filter"] == "box");
  CHECK(film("<rfilter type=\"box\"><float name=\"radius\" value=\"0.5\"/></rfilter>").doc["render"]["filter"] == "box");
  // A sensor without a film, and a scene without a sensor: Mitsuba's default film, Gaussian.
  const nlohmann::json gaussian = {{"type", "gaussian"}, {"stddev", 0.5}};
  CHECK(read_mitsuba("<scene version=\"3.0.0\"><sensor type=\"perspective\"/></scene>", "s.xml", ".", {})
            .doc["render"]["filter"] == gaussian);
  CHECK(read_mitsuba("<scene version=\"3.0.0\"/>", "s.xml", ".", {}).doc["render"]["filter"] == gaussian);
  CHECK(film("<rfilter type=\"tent\"><float name=\"radius\" value=\"1.5\"/></rfilter>").doc["render"]["filter"] ==
        nlohmann::json({{"type", "tent"}, {"radius", 1.5}}));
  // A filter with negative lobes: the Gaussian, with a warning.
  const TranslatedScene m = film("<rfilter type=\"mitchell\"/>");
  CHECK(m.doc["render"]["filter"] == nlohmann::json({{"type", "gaussian"}, {"stddev", 0.5}}));
  REQUIRE(m.warnings.size() == 1);
  CHECK(m.warnings[0].find("\"mitchell\" is rendered as a Gaussian") != std::string::npos);
}
