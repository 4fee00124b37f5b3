// Pixel filters: samples distributed as the filter (moments and a quantile), and Mitsuba's rfilter.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "io/mitsuba/translate.h"
#include "core/pixel_filter.h"
#include "io/scene_loader.h"

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

TEST_CASE("pixel filter: box, Gaussian and tent samples follow the filter", "[filter]" TIER_UNIT) {
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

TEST_CASE("pixel filter: Mitsuba's rfilter and its default", "[filter][mitsuba]" TIER_UNIT) {
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
  // Filters with negative lobes, with their parameters.
  const TranslatedScene m = film("<rfilter type=\"mitchell\"/>");
  CHECK(m.doc["render"]["filter"] == nlohmann::json({{"type", "mitchell"}}));
  CHECK(m.warnings.empty());
  CHECK(film("<rfilter type=\"mitchell\"><float name=\"B\" value=\"0.5\"/><float name=\"C\" value=\"0.25\"/></rfilter>")
            .doc["render"]["filter"] == nlohmann::json({{"type", "mitchell"}, {"B", 0.5}, {"C", 0.25}}));
  CHECK(film("<rfilter type=\"catmullrom\"/>").doc["render"]["filter"] == nlohmann::json({{"type", "catmullrom"}}));
  CHECK(film("<rfilter type=\"lanczos\"><integer name=\"lobes\" value=\"2\"/></rfilter>").doc["render"]["filter"] ==
        nlohmann::json({{"type", "lanczos"}, {"lobes", 2}}));
  CHECK_THROWS_WITH(film("<rfilter type=\"sinc\"/>"), Catch::Contains("unknown reconstruction filter \"sinc\""));
}

namespace {
// The weighted sample moments E[w], E[w x^2] and the share of negative weights, over a
// stratified grid of u, and E[w |x|], against the filter's own profile integrated by a fine midpoint rule
// (independent of the sampling table): integral of f x^2 / integral of f.
void check_signed_filter(const PixelFilter& f, double expect_negative_share) {
  constexpr int n = 400000;
  double w_sum = 0, wx2_sum = 0, wabs_sum = 0, negative = 0;
  int outside = 0;
  for (int i = 0; i < n; ++i) {
    float w = 0;
    const float x = f.sample(Vec2((float(i) + 0.5f) / n, 0.5f), &w).x;
    outside += std::abs(x) > f.radius();
    w_sum += w;
    wx2_sum += w * double(x) * x;
    wabs_sum += w * std::abs(double(x));
    negative += w < 0;
  }
  // The y sample at u = 0.5 is at the centre (positive), so w = sign(f(x)) norm^2, and under
  // sampling by |f| the mean of sign(f(x)) is 1 / norm.
  double fi = 0, fx2 = 0, fxabs = 0, fabs = 0;
  constexpr int m = 200000;
  for (int i = 0; i < m; ++i) {
    const double x = -f.radius() + 2.0 * f.radius() * (i + 0.5) / m;
    const double v = f.profile(x);
    fi += v;
    fx2 += v * x * x;
    fxabs += v * std::abs(x);
    fabs += std::abs(v);
  }
  const double norm = fabs / fi;
  CHECK(outside == 0);
  CHECK(w_sum / n == Approx(norm).epsilon(1e-3));
  // Catmull-Rom and Lanczos interpolate: their second moment is 0, hence the margin.
  CHECK(wx2_sum / n / norm == Approx(fx2 / fi).epsilon(2e-3).margin(1e-4));
  CHECK(wabs_sum / n / norm == Approx(fxabs / fi).epsilon(2e-3));
  CHECK(negative / n == Approx(expect_negative_share).margin(0.01));
  CHECK(f.has_negative_lobes() == (expect_negative_share > 0));
}
}  // namespace

TEST_CASE("pixel filter: Mitchell, Catmull-Rom and Lanczos, negative lobes weighted", "[filter]" TIER_UNIT) {
  // Mitchell-Netravali at B = C = 1/3: f(0) = (6 - 2B) / 6, zero at |x| = 2, negative beyond
  // about 1.27 pixels.
  const PixelFilter mitchell = PixelFilter::mitchell(1.0f / 3.0f, 1.0f / 3.0f);
  CHECK(mitchell.profile(0.0) == Approx(8.0 / 9.0));
  CHECK(mitchell.profile(1.0) == Approx(1.0 / 18.0));
  CHECK(mitchell.profile(1.5) < 0.0);
  CHECK(mitchell.profile(2.0) == Approx(0.0).margin(1e-12));
  // The share of |f| in the negative lobes: integral over 1..2 of max(0, -f) / integral of |f|.
  auto negative_share = [](const PixelFilter& f) {
    double neg = 0, all = 0;
    for (int i = 0; i < 100000; ++i) {
      const double x = -f.radius() + 2.0 * f.radius() * (i + 0.5) / 100000;
      all += std::abs(f.profile(x));
      neg += std::max(0.0, -f.profile(x));
    }
    return neg / all;
  };
  check_signed_filter(mitchell, negative_share(mitchell));
  const PixelFilter catmull = PixelFilter::mitchell(0.0f, 0.5f, "catmullrom");
  CHECK(catmull.profile(0.0) == Approx(1.0));  // Catmull-Rom interpolates: f(0) = 1, f(1) = 0
  CHECK(catmull.profile(1.0) == Approx(0.0).margin(1e-12));
  check_signed_filter(catmull, negative_share(catmull));
  const PixelFilter lanczos = PixelFilter::lanczos(3);
  CHECK(lanczos.radius() == 3.0f);
  CHECK(lanczos.profile(0.5) == Approx(std::sin(kPi * 0.5) / (kPi * 0.5) * std::sin(kPi / 6) / (kPi / 6)));
  check_signed_filter(lanczos, negative_share(lanczos));
  // Positive filters keep weight 1.
  float w = 0;
  PixelFilter::gaussian(0.5f).sample(Vec2(0.3f, 0.9f), &w);
  CHECK(w == 1.0f);
  CHECK_FALSE(PixelFilter::tent(1.0f).has_negative_lobes());
}

TEST_CASE("pixel filter: the JSON scene's filter and its errors", "[filter]" TIER_UNIT) {
  auto scene_with = [](const std::string& filter) {
    return parse_scene(R"({"render": {"width": 8, "height": 8, "filter": )" + filter +
                           R"(}, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {"w": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "w"}]})",
                       "f.json", ".");
  };
  CHECK(scene_with(R"("catmullrom")").scene->render.filter.name() == "catmullrom");
  const LoadedScene m = scene_with(R"({"type": "mitchell", "B": 0, "C": 0.5})");
  CHECK(m.scene->render.filter.profile(1.0) == Approx(0.0).margin(1e-12));  // = Catmull-Rom
  CHECK(scene_with(R"({"type": "lanczos", "lobes": 2})").scene->render.filter.radius() == 2.0f);
  CHECK_THROWS_WITH(scene_with(R"({"type": "mitchell", "B": 7})"), Catch::Contains("f.json: /render/filter/B"));
  CHECK_THROWS_WITH(scene_with(R"({"type": "lanczos", "lobes": 0})"), Catch::Contains("/render/filter/lobes"));
  CHECK_THROWS_WITH(scene_with(R"("sinc")"), Catch::Contains("unknown filter \"sinc\" (known: box, gaussian, tent, mitchell, catmullrom, lanczos)"));
  CHECK_THROWS_WITH(scene_with(R"({"type": "catmullrom", "B": 1})"), Catch::Contains("/render/filter"));
}
