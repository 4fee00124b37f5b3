// The Cornell box written in Mitsuba 3's format renders like our JSON Cornell box.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "support/render_util.h"

using namespace caustica;
using namespace caustica::test;

namespace {
glm::dvec3 image_mean(const Image& img) { return region_mean(img, 0, 0, img.width, img.height); }
}  // namespace

TEST_CASE("Mitsuba 3 Cornell box renders with path within 2 percent of the JSON Cornell box", "[mitsuba]" TIER_UNIT) {
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

TEST_CASE("hide_emitters hides the emission the camera sees directly, in path and photon", "[mitsuba]" TIER_UNIT) {
  const std::string dir = std::string(CAUSTICA_SOURCE_DIR) + "/scenes";
  const std::string scene = read_scene_file("scenes/cornell-box.json");
  for (const char* integrator : {"path", "photon"}) {
    INFO(integrator);
    const std::string extra = std::string(integrator) == "photon" ? R"(, "photons": 20000, "caustic_photons": 0)" : "";
    const TestRender shown = render_text(scene, integrator, "{}", 4, 64, 64, 3, 0, dir);
    const TestRender hidden = render_text(scene, integrator, R"({"hide_emitters": true)" + extra + "}", 4, 64, 64, 3, 0, dir);
    // The light fills pixels x 28..35, y 8..9 of the 64x64 image; the wall below it is lit.
    const glm::dvec3 light_shown = region_mean(shown.image, 28, 8, 36, 10), light_hidden = region_mean(hidden.image, 28, 8, 36, 10);
    // Hidden, the light shows only what its own diffuse surface (albedo 0.78) reflects.
    CHECK(light_shown.x > 5.0);
    CHECK(light_hidden.x < 0.3);
    CHECK(light_hidden.x > 0.0);
    const glm::dvec3 wall = region_mean(hidden.image, 24, 24, 40, 40);
    CHECK(wall.x > 0.05);
  }
  // The Mitsuba integrator's hide_emitters reaches our settings.
  const nlohmann::json doc = read_mitsuba(R"(<scene version="3.0.0"><integrator type="path">
    <boolean name="hide_emitters" value="true"/></integrator></scene>)", "s.xml", ".", {}).doc;
  CHECK(doc["integrator"]["hide_emitters"] == true);
}
