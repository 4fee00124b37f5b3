// Mitsuba's curve files: every fault an error naming the file and the line; the reader fuzzed.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include "core/error.h"
#include "core/rng.h"
#include "io/curve_io.h"
#include "io/scene_loader.h"
#include "support/errors.h"
#include "support/random.h"
#include "support/temp_dir.h"

using namespace caustica;

TEST_CASE("curve files: each fault is an error naming the file and the line", "[curve][io]" TIER_UNIT) {
  const auto curves = parse_curves("-1 0.1 0.1 0.5\n1 1.4 1.2 0.5\n\n-1 5 2.2 1\n-2.3 4 2.3 2\n4 1 2.2 5\n", "c.txt", 2);
  REQUIRE(curves.size() == 2);
  CHECK(curves[0].size() == 2);
  CHECK(curves[1].size() == 3);
  CHECK(curves[1][2] == glm::vec4(4.0f, 1.0f, 2.2f, 5.0f));
  auto error = [](const std::string& text, size_t min = 2) { return test::error_of([&] { parse_curves(text, "c.txt", min); }); };
  CHECK_THAT(error("0 0 0 1\n1 1 1\n"), Catch::Contains("c.txt:2") && Catch::Contains("four numbers"));
  CHECK_THAT(error("0 0 0 1\n1 1 1 1 7\n"), Catch::Contains("c.txt:2") && Catch::Contains("more than four"));
  CHECK_THAT(error("0 0 0 1\n1 nan 1 1\n"), Catch::Contains("c.txt:2") && Catch::Contains("not finite"));
  CHECK_THAT(error("0 0 0 1\n1 1 1 -0.5\n"), Catch::Contains("c.txt:2") && Catch::Contains("negative"));
  CHECK_THAT(error("0 0 0 1\n1 1 1 1\n\n2 2 2 1\n"), Catch::Contains("c.txt:4") && Catch::Contains("at least 2"));
  CHECK_THAT(error("0 0 0 1\n1 1 1 1\n2 2 2 1\n", 4), Catch::Contains("c.txt:1") && Catch::Contains("at least 4"));
  CHECK_THAT(error("\n  \n"), Catch::Contains("no control points"));
  CHECK_THAT(test::error_of([] { read_curve_file("/nonexistent/c.txt", 2); }), Catch::Contains("/nonexistent/c.txt"));
}

TEST_CASE("curve files: random corruptions never crash the reader (fuzz)", "[curve][io][fuzz]" TIER_UNIT) {
  const std::string good = "-1 0.1 0.1 0.5\n1 1.4 1.2 0.5\n\n-1 5 2.2 1\n-2.3 4 2.3 2\n4 1 2.2 5\n";
  Rng rng(5);
  int errors = 0;
  for (int i = 0; i < 5000; ++i) {
    const std::string b = test::corrupt(good, rng, 0.3f);
    try {
      for (const auto& c : parse_curves(b, "fuzz.txt", 2)) {
        REQUIRE(c.size() >= 2);
        for (const glm::vec4& v : c) REQUIRE((std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.w >= 0.0f));
      }
    } catch (const InputError&) {
      ++errors;
    }
  }
  CHECK(errors > 1000);
}

TEST_CASE("linearcurve: Mitsuba's linearcurve in an instance: positions by both transforms, radii as written",
          "[curve][io][mitsuba]" TIER_UNIT) {
  test::TempDir dir;
  dir.write("wire.txt", "0 0 0 0.1\n1 0 0 0.1\n\n0 0 1 0.05\n0.5 0 1 0.05\n1 0 1 0.05\n");
  const std::string xml = dir.write("scene.xml", R"(<scene version="3.0.0">
  <shape type="shapegroup" id="wires">
    <shape type="linearcurve"><string name="filename" value="wire.txt"/>
      <transform name="to_world"><scale value="2"/></transform></shape>
  </shape>
  <shape type="instance"><ref id="wires"/><transform name="to_world"><translate y="1"/></transform></shape>
</scene>)");
  const LoadedScene loaded = load_scene(xml);
  const Scene& scene = *loaded.scene;
  SurfaceHit hit;
  // The first curve, from (0, 1, 0) to (2, 1, 0), radius 0.1 (not 0.2: to_world moves the points only).
  REQUIRE(scene.intersect(Ray{Vec3(1.0f, 5.0f, 0.0f), Vec3(0, -1, 0), kInfinity}, hit));
  CHECK(hit.t == Approx(3.9f).margin(1e-4));
  CHECK(hit.n.y == Approx(1.0f).margin(1e-4));
  CHECK(hit.sp.uv.y == Approx((0.5f + 0.0f) / 3.0f).margin(1e-3));  // v: half way along segment 0 of 3
  // The second, at z = 2, radius 0.05, its two segments the file's 1 and 2.
  REQUIRE(scene.intersect(Ray{Vec3(1.5f, 5.0f, 2.0f), Vec3(0, -1, 0), kInfinity}, hit));
  CHECK(hit.t == Approx(3.95f).margin(1e-4));
  CHECK(hit.sp.uv.y == Approx((0.5f + 2.0f) / 3.0f).margin(1e-3));
  // A curve file with a lone point is an error naming the file and the line.
  dir.write("bad.txt", "0 0 0 0.1\n1 0 0 0.1\n\n5 5 5 0.1\n");
  const std::string bad = dir.write("bad.xml", R"(<scene version="3.0.0"><shape type="linearcurve"><string name="filename" value="bad.txt"/></shape></scene>)");
  CHECK_THAT(test::error_of([&] { load_scene(bad); }), Catch::Contains("bad.txt:4") && Catch::Contains("at least 2"));
}

TEST_CASE("bsplinecurve: Mitsuba's bsplinecurve: n - 3 segments a curve, hit on the spline's sweep", "[curve][io][mitsuba]" TIER_UNIT) {
  test::TempDir dir;
  // A straight spline along x: control points at x = -1, 0, 1, 2, 3 make two segments covering
  // x in [0, 2] (a uniform cubic B-spline of equally spaced points is the line between the
  // second and the second to last), radius 0.2.
  dir.write("line.txt", "-1 0 0 0.2\n0 0 0 0.2\n1 0 0 0.2\n2 0 0 0.2\n3 0 0 0.2\n");
  const std::string xml = dir.write("scene.xml", R"(<scene version="3.0.0">
  <shape type="bsplinecurve"><string name="filename" value="line.txt"/>
    <transform name="to_world"><translate z="1"/></transform></shape>
</scene>)");
  const LoadedScene loaded = load_scene(xml);
  const Scene& scene = *loaded.scene;
  REQUIRE(scene.curve_points.size() == 1);
  CHECK(scene.curve_points[0]->size() == 8);  // two segments of four points
  SurfaceHit hit;
  REQUIRE(scene.intersect(Ray{Vec3(1.5f, 5.0f, 1.0f), Vec3(0, -1, 0), kInfinity}, hit));
  CHECK(hit.t == Approx(4.8f).margin(1e-4));
  CHECK(hit.n.y == Approx(1.0f).margin(1e-4));
  CHECK(hit.sp.uv.y == Approx((0.5f + 1.0f) / 2.0f).margin(1e-3));  // half way along segment 1 of 2
  // Open at the ends: past x = 2 (and before 0) nothing, also along the axis into its end.
  CHECK_FALSE(scene.intersect(Ray{Vec3(2.1f, 5.0f, 1.0f), Vec3(0, -1, 0), kInfinity}, hit));
  // A curve of 3 points is too short for a cubic segment.
  dir.write("short.txt", "0 0 0 0.1\n1 0 0 0.1\n2 0 0 0.1\n");
  const std::string bad = dir.write("bad.xml", R"(<scene version="3.0.0"><shape type="bsplinecurve"><string name="filename" value="short.txt"/></shape></scene>)");
  CHECK_THAT(test::error_of([&] { load_scene(bad); }), Catch::Contains("short.txt:1") && Catch::Contains("at least 4"));
}
