// The HTML report: a self-contained page (embedded PNGs, escaped text, no network) that loads
// without script errors in headless Chromium when it is installed.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include "app/report.h"
#include "io/image_io.h"
#include "io/json_reader.h"
#include "support/temp_dir.h"

using namespace caustica;
namespace fs = std::filesystem;

namespace {

// A smooth test picture with a bright disc, plus deterministic noise of amplitude `noise`.
Image picture(int w, int h, float noise, uint32_t seed) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      seed = seed * 1664525u + 1013904223u;
      const float n = noise * (float(seed >> 8) / float(1u << 24) - 0.5f);
      const float disc = std::hypot(x - 0.6f * w, y - 0.5f * h) < 0.2f * h ? 2.0f : 0.0f;
      img.at(x, y) = glm::max(Color(float(x) / w, float(y) / h, 0.3f) * 0.5f + disc + n, Color(0.0f));
    }
  }
  return img;
}

ReportData sample_report(const test::TempDir& dir) {
  ReportData data;
  data.title = "<b>scene & \"spheres\"</b>";
  data.facts = {{"scene", "cornell <spheres>.json"}, {"budget", "2 s per integrator"}};
  const char* names[] = {"reference", "path", "photon", "path error", "photon error"};
  for (int i = 0; i < 5; ++i) {
    const std::string file = std::string(names[i]) + ".png";
    write_image(dir.file(file), picture(96 + i, 64, i == 0 ? 0.0f : 0.3f, uint32_t(i)));
    data.images.push_back({names[i], file});
  }
  ReportSeries path{"path", {}}, photon{"photon <pm>", {}};
  for (int k = 0; k < 6; ++k) {
    const double t = 0.05 * std::pow(2.0, k);
    path.points.push_back({t, 0.5 / t, std::sqrt(0.5 / t), long(1) << k});
    photon.points.push_back({t, 0.02 / std::sqrt(t) + 0.01, 0.1, long(1) << k});
  }
  photon.points.push_back({0.0, 0.1, 0.1, 0});  // not plottable: no time
  path.points.push_back({5.0, 0.0, 0.0, 99});  // not plottable: no error
  data.series = {path, photon, ReportSeries{"empty", {}}};
  return data;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string base64_decode(const std::string& text) {
  const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=') break;
    bits = (bits << 6) | uint32_t(digits.find(c));
    if ((count += 6) >= 8) out += char((bits >> (count -= 8)) & 0xff);
  }
  return out;
}

int run(const std::string& command) { return std::system(("timeout 60 " + command + " >/dev/null 2>&1").c_str()); }

}  // namespace

TEST_CASE("report: a self-contained page with every image embedded", "[app][report]" TIER_UNIT) {
  test::TempDir dir;
  const ReportData data = sample_report(dir);
  write_report(dir.path().string(), data);
  REQUIRE(fs::is_regular_file(dir.file("index.html")));
  const std::string html = test::read_text(dir.file("index.html"));

  CHECK(count_of(html, "data:image/png;base64,") == data.images.size());
  // Each URI decodes back to the PNG file it came from.
  // (std::regex recurses per character: on megabytes of base64 it overflows the stack under ASan.)
  const std::string prefix = "data:image/png;base64,";
  size_t i = 0;
  for (size_t at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at + 1), ++i) {
    REQUIRE(i < data.images.size());
    const size_t start = at + prefix.size(), end = html.find('"', start);
    REQUIRE(end != std::string::npos);
    CHECK(base64_decode(html.substr(start, end - start)) == test::read_text(dir.file(data.images[i].file)));
  }
  CHECK(i == data.images.size());

  CHECK(html.find("&lt;b&gt;scene &amp; &quot;spheres&quot;&lt;/b&gt;") != std::string::npos);
  CHECK(html.find("cornell &lt;spheres&gt;.json") != std::string::npos);
  CHECK(html.find("photon &lt;pm&gt;") != std::string::npos);
  CHECK(html.find(data.title) == std::string::npos);
  CHECK(html.find("<pm>") == std::string::npos);
  CHECK(html.find("http://") == std::string::npos);
  CHECK(html.find("https://") == std::string::npos);
  CHECK(html.find("<pre id=\"selftest\">") != std::string::npos);
  CHECK(count_of(html, "class=\"series\"") == 2);  // "empty" has no points to draw

  for (const auto& entry : fs::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    CHECK((name == "index.html" || entry.path().extension() == ".png"));
  }
}

TEST_CASE("report: a missing image or folder is an input error naming it", "[app][report]" TIER_UNIT) {
  test::TempDir dir;
  ReportData data = sample_report(dir);
  data.images.push_back({"lost", "missing.png"});
  CHECK_THROWS_WITH(write_report(dir.path().string(), data), Catch::Contains("missing.png"));
  CHECK_THROWS_AS(write_report(dir.path().string(), data), InputError);
  CHECK_FALSE(fs::exists(dir.file("index.html")));

  dir.write("fake.png", "not a png");
  data.images.back() = {"fake", "fake.png"};
  CHECK_THROWS_WITH(write_report(dir.path().string(), data), Catch::Contains("fake.png"));

  const std::string nowhere = dir.file("no-such-folder");
  CHECK_THROWS_AS(write_report(nowhere, ReportData{}), InputError);
  CHECK_THROWS_WITH(write_report(nowhere, ReportData{}), Catch::Contains("no-such-folder"));
}

TEST_CASE("report: loads without errors in headless Chromium", "[app][report]" TIER_PROCESS) {
  // scripts/test.sh installs Chromium, so a missing browser is a failure, not a silent skip.
  // CAUSTICA_NO_BROWSER=1 opts out explicitly (a developer machine without a browser).
  if (std::getenv("CAUSTICA_NO_BROWSER") != nullptr) {
    WARN("CAUSTICA_NO_BROWSER is set: browser test skipped");
    return;
  }
  INFO("/usr/bin/chromium is missing: run `bash scripts/setup.sh chromium` (scripts/test.sh does)");
  REQUIRE(fs::exists("/usr/bin/chromium"));
  test::TempDir dir;
  const ReportData data = sample_report(dir);
  write_report(dir.path().string(), data);
  const std::string chromium = "/usr/bin/chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage "
                               "--disable-background-networking --disable-component-update --disable-sync "
                               "--no-first-run --user-data-dir='" + dir.file("profile") + "' --virtual-time-budget=5000 ";
  const std::string page = "'file://" + dir.file("index.html") + "'";

  const std::string dom = dir.file("dom.html");
  REQUIRE(std::system(("timeout 60 " + chromium + "--dump-dom " + page + " >'" + dom + "' 2>/dev/null").c_str()) == 0);
  const std::string text = test::read_text(dom);
  const std::string open_tag = "<pre id=\"selftest\">";
  const size_t at = text.find(open_tag);
  REQUIRE(at != std::string::npos);
  const size_t start = at + open_tag.size();
  const std::string selftest = text.substr(start, text.find('<', start) - start);
  INFO("selftest: " << selftest);
  CHECK(selftest == "images=5 loaded=5 plot_series=2 errors=0");

  const std::string shot = dir.file("shot.png");
  REQUIRE(run(chromium + "--screenshot='" + shot + "' --window-size=1400,1000 " + page) == 0);
  REQUIRE(fs::is_regular_file(shot));
  CHECK(fs::file_size(shot) > 20000);
  const Image image = read_image(shot);
  double sum = 0, sum2 = 0;
  for (const Color& c : image.pixels) {
    const double v = (c.x + c.y + c.z) / 3.0;
    sum += v, sum2 += v * v;
  }
  const double mean = sum / double(image.pixels.size());
  CHECK(sum2 / double(image.pixels.size()) - mean * mean > 1e-3);
}

TEST_CASE("report: the convergence slope is the late log-log slope of relMSE against time", "[app][report]" TIER_UNIT) {
  ReportSeries noise{"noise", {}}, floor{"floor", {}}, mixed{"mixed", {}}, short_run{"short", {}};
  for (double t = 1; t <= 64; t *= 2) {
    noise.points.push_back({t, 0.1 / t, 0, 1});
    floor.points.push_back({t, 0.01, 0, 1});
    // 1/t noise over a bias floor of 0.001: steep early, flat late.
    mixed.points.push_back({t, 0.1 / t + 0.001, 0, 1});
  }
  short_run.points.push_back({5, 0.1, 0, 1});
  CHECK(convergence_slope(noise) == Approx(-1.0).margin(1e-9));
  CHECK(convergence_slope(floor) == Approx(0.0).margin(1e-9));
  // From 16 s on (a quarter of 64): log(0.1/t + 0.001) over t = 16, 32, 64.
  const double x[3] = {std::log(16.0), std::log(32.0), std::log(64.0)};
  double y[3];
  for (int i = 0; i < 3; ++i) y[i] = std::log(0.1 / std::exp(x[i]) + 0.001);
  const double mx = (x[0] + x[1] + x[2]) / 3, my = (y[0] + y[1] + y[2]) / 3;
  double num = 0, den = 0;
  for (int i = 0; i < 3; ++i) num += (x[i] - mx) * (y[i] - my), den += (x[i] - mx) * (x[i] - mx);
  CHECK(convergence_slope(mixed) == Approx(num / den).epsilon(1e-9));
  CHECK(convergence_slope(mixed) > -0.9);
  CHECK(std::isnan(convergence_slope(short_run)));
}
