// The Cornell box written in Mitsuba 3's format renders like our JSON Cornell box.
#include <catch2/catch.hpp>
#include "support/render_util.h"

using namespace caustica;
using namespace caustica::test;

namespace {
glm::dvec3 image_mean(const Image& img) { return region_mean(img, 0, 0, img.width, img.height); }
}  // namespace

TEST_CASE("Mitsuba 3 Cornell box renders with path within 2 percent of the JSON Cornell box", "[mitsuba]") {
  const std::string dir = std::string(CAUSTICA_SOURCE_DIR) + "/scenes";
  const TestRender json = render_text(read_scene_file("scenes/cornell-box.json"), "path", "{}", 64, 64, 64, 3, 0, dir);
  const TestRender xml =
      render_text(read_scene_file("scenes/mitsuba/cornell-box.xml"), "path", "{}", 64, 64, 64, 3, 0, dir + "/mitsuba");
  const glm::dvec3 a = image_mean(json.image), b = image_mean(xml.image);
  INFO("JSON mean " << a.x << " " << a.y << " " << a.z << ", XML mean " << b.x << " " << b.y << " " << b.z);
  REQUIRE(a.x > 0.05);  // not black: the light and the walls are there
  for (int c = 0; c < 3; ++c) REQUIRE(b[c] == Approx(a[c]).epsilon(0.02));
  // The red wall is on the left and the green on the right in both.
  for (const Image* img : {&json.image, &xml.image}) {
    const glm::dvec3 left = region_mean(*img, 2, 24, 8, 40), right = region_mean(*img, 56, 24, 62, 40);
    REQUIRE(left.x > 2.0 * left.y);
    REQUIRE(right.y > 2.0 * right.x);
  }
}
