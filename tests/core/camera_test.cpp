// The camera: a thin lens focuses every ray of a pixel on one point of the plane of focus.
#include <catch2/catch.hpp>
#include "core/camera.h"
#include "io/mitsuba/translate.h"
#include "support/errors.h"
#include "support/random.h"

using namespace caustica;

TEST_CASE("camera: thin-lens rays of a pixel start on the aperture and meet on the plane of focus", "[camera]") {
  Camera cam(Vec3(1, 2, 3), Vec3(1, 2, -7), Vec3(0, 1, 0), 40.0f, 64, 48);
  const Vec3 forward(0, 0, -1);
  cam.set_lens(0.25f, 6.0f);
  REQUIRE(cam.has_lens());
  Rng rng(5);
  for (const auto& px : {glm::ivec2(0, 0), glm::ivec2(31, 20), glm::ivec2(63, 47)}) {
    const Vec2 jitter(0.3f, 0.7f);
    const Ray pinhole = cam.generate_ray(px.x, px.y, jitter);
    const Vec3 focus = pinhole.origin + pinhole.dir * (6.0f / glm::dot(pinhole.dir, forward));
    float max_offset = 0.0f;
    for (int i = 0; i < 200; ++i) {
      const Ray r = cam.generate_ray(px.x, px.y, jitter, test::next2(rng));
      const Vec3 offset = r.origin - Vec3(1, 2, 3);
      CHECK(std::abs(glm::dot(offset, forward)) < 1e-6f);  // on the lens plane
      CHECK(glm::length(offset) <= 0.25f + 1e-6f);          // inside the aperture
      max_offset = std::max(max_offset, glm::length(offset));
      const Vec3 at = r.origin + r.dir * (glm::dot(focus - r.origin, forward) / glm::dot(r.dir, forward));
      CHECK(glm::length(at - focus) < 1e-4f);
    }
    CHECK(max_offset > 0.2f);  // the samples cover the aperture
  }
  // Radius 0 is the pinhole again.
  cam.set_lens(0.0f, 6.0f);
  const Ray a = cam.generate_ray(5, 6, Vec2(0.5f), Vec2(0.9f, 0.1f)), b = cam.generate_ray(5, 6, Vec2(0.5f));
  CHECK(a.origin == b.origin);
  CHECK(a.dir == b.dir);
}

TEST_CASE("camera: Mitsuba's thinlens maps to aperture_radius and focus_distance", "[camera][mitsuba]") {
  const std::string sensor = R"(<scene version="3.0.0"><sensor type="thinlens"><float name="fov" value="30"/>
    <float name="aperture_radius" value="0.1"/><float name="focus_distance" value="4.5"/></sensor></scene>)";
  const nlohmann::json doc = read_mitsuba(sensor, "s.xml", ".", {}).doc;
  CHECK(doc["camera"]["aperture_radius"] == 0.1);
  CHECK(doc["camera"]["focus_distance"] == 4.5);
  const std::string missing = R"(<scene version="3.0.0"><sensor type="thinlens"><float name="fov" value="30"/></sensor></scene>)";
  CHECK(test::error_of([&] { read_mitsuba(missing, "s.xml", ".", {}); }) ==
        "s.xml:1:25: <sensor type=\"thinlens\">: a thinlens sensor needs aperture_radius and focus_distance");
}
