// The camera: a thin lens focuses every ray of a pixel on one point of the plane of focus.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/camera.h"
#include "io/mitsuba/translate.h"
#include "io/scene_loader.h"
#include "support/render_util.h"
#include "support/errors.h"
#include "support/random.h"

using namespace caustica;

TEST_CASE("camera: thin-lens rays of a pixel start on the aperture and meet on the plane of focus", "[camera]" TIER_UNIT) {
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

TEST_CASE("camera: Mitsuba's thinlens maps to aperture_radius and focus_distance", "[camera][mitsuba]" TIER_UNIT) {
  const std::string sensor = R"(<scene version="3.0.0"><sensor type="thinlens"><float name="fov" value="30"/>
    <float name="aperture_radius" value="0.1"/><float name="focus_distance" value="4.5"/></sensor></scene>)";
  const nlohmann::json doc = read_mitsuba(sensor, "s.xml", ".", {}).doc;
  CHECK(doc["camera"]["aperture_radius"] == 0.1);
  CHECK(doc["camera"]["focus_distance"] == 4.5);
  const std::string missing = R"(<scene version="3.0.0"><sensor type="thinlens"><float name="fov" value="30"/></sensor></scene>)";
  CHECK(test::error_of([&] { read_mitsuba(missing, "s.xml", ".", {}); }) ==
        "s.xml:1:25: <sensor type=\"thinlens\">: a thinlens sensor needs aperture_radius and focus_distance");
}

TEST_CASE("camera: orthographic rays are parallel, from a rectangle of the given size, and project back", "[camera]" TIER_UNIT) {
  Camera cam(Vec3(1, 2, 3), Vec3(1, 2, -7), Vec3(0, 1, 0), 40.0f, 64, 32);
  cam.set_orthographic(8.0f, 0.0f);  // 8 wide, 4 high: the film's aspect
  REQUIRE(cam.orthographic());
  const Ray corner = cam.generate_ray(0.0f, 0.0f), centre = cam.generate_ray(32.0f, 16.0f);
  const Ray far_corner = cam.generate_ray(64.0f, 32.0f);
  CHECK(glm::length(centre.dir - Vec3(0, 0, -1)) < 1e-6f);
  CHECK(glm::length(corner.dir - Vec3(0, 0, -1)) < 1e-6f);
  // Image right is world +x here (looking down -z with +y up), image top +y.
  CHECK(glm::length(corner.origin - Vec3(1 - 4, 2 + 2, 3)) < 1e-5f);
  CHECK(glm::length(far_corner.origin - Vec3(1 + 4, 2 - 2, 3)) < 1e-5f);
  CHECK(glm::length(centre.origin - Vec3(1, 2, 3)) < 1e-6f);
  // project() inverts generate_ray at any depth in front of the plane.
  Rng rng(3);
  for (int i = 0; i < 100; ++i) {
    const Vec2 f = test::next2(rng) * Vec2(64.0f, 32.0f);
    const Ray r = cam.generate_ray(f.x, f.y);
    float x = 0, y = 0;
    REQUIRE(cam.project(r.origin + r.dir * (1.0f + 50.0f * test::next2(rng).x), x, y));
    CHECK(x == Approx(f.x).margin(1e-3));
    CHECK(y == Approx(f.y).margin(1e-3));
    CHECK(cam.eye_for(r.origin + 3.0f * r.dir) == r.origin);
  }
  // A given height: non-square pixels.
  cam.set_orthographic(8.0f, 1.0f);
  CHECK(cam.generate_ray(0.0f, 0.0f).origin.y == Approx(2.5f));
}

TEST_CASE("camera: an orthographic camera sees an emitting square at its true size", "[camera]" TIER_UNIT) {
  // A 2 x 2 emitter of radiance 3 in a 4 x 4 view covers a quarter of the image, its edges on
  // pixel boundaries: the image mean is 3 / 4 exactly, at any distance.
  for (const char* z : {"-1", "-40"}) {
    const std::string scene = std::string(R"({"render": {"width": 16, "height": 16},
      "camera": {"type": "orthographic", "position": [0, 0, 5], "look_at": [0, 0, 0], "view_width": 4},
      "materials": {"e": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [3, 3, 3]}},
      "objects": [{"type": "mesh", "material": "e", "vertices": [[-1, -1, )") + z + "], [1, -1, " + z + "], [1, 1, " + z +
                              "], [-1, 1, " + z + R"(]], "indices": [[0, 1, 2], [0, 2, 3]]}]})";
    const test::TestRender r = test::render_text(scene, "path", "{}", 4, 16, 16);
    CHECK(test::region_mean(r.image, 0, 0, 16, 16).x == Approx(0.75).epsilon(1e-6));
    CHECK(test::region_mean(r.image, 4, 4, 12, 12).y == Approx(3.0).epsilon(1e-6));
  }
}

TEST_CASE("camera: Mitsuba's orthographic sensor", "[camera][mitsuba]" TIER_UNIT) {
  auto doc = [](const std::string& inner, const std::string& film = "") {
    return read_mitsuba(R"(<scene version="3.0.0"><sensor type="orthographic">)" + inner + film + "</sensor></scene>",
                        "s.xml", ".", {})
        .doc;
  };
  // Default: camera space x in [-1, 1], rays from the near plane (0.01 ahead).
  nlohmann::json d = doc("");
  CHECK(d["camera"]["type"] == "orthographic");
  CHECK(d["camera"]["view_width"] == 2.0);
  CHECK_FALSE(d["camera"].contains("view_height"));
  CHECK(d["camera"]["position"][2].get<double>() == Approx(0.01));
  // to_world's scale sizes the view; a y scale unlike x's sets the height, with the film's aspect.
  d = doc(R"(<transform name="to_world"><scale x="5" y="5" z="1"/><lookat origin="0, 0, 10" target="0, 0, 0" up="0, 1, 0"/></transform>
             <float name="near_clip" value="1"/>)");
  CHECK(d["camera"]["view_width"].get<double>() == Approx(10.0));
  CHECK(d["camera"]["position"][2].get<double>() == Approx(9.0));
  d = doc(R"(<transform name="to_world"><scale x="5" y="2" z="1"/></transform>)",
          R"(<film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="20"/></film>)");
  CHECK(d["camera"]["view_width"].get<double>() == Approx(10.0));
  CHECK(d["camera"]["view_height"].get<double>() == Approx(2.0));  // y in [-2 / 2, 2 / 2]
}

TEST_CASE("camera: orthographic camera keys are checked", "[camera]" TIER_UNIT) {
  auto error = [](const std::string& camera) {
    return test::error_of([&] {
      parse_scene(R"({"camera": )" + camera + R"(, "materials": {"w": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
                  "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "w"}]})",
                  "c.json", ".");
    });
  };
  const std::string base = R"("position": [0, 0, 5], "look_at": [0, 0, 0])";
  CHECK(error("{" + base + R"(, "type": "orthographic"})") == "c.json: /camera: missing required key \"view_width\"");
  CHECK(error("{" + base + R"(, "type": "orthographic", "view_width": 2, "fov": 30})") ==
        "c.json: /camera/fov: fov does not apply to an orthographic camera");
  CHECK(error("{" + base + R"(, "view_width": 2})") ==
        "c.json: /camera/view_width: view_width applies to an orthographic camera only (\"type\": \"orthographic\")");
  CHECK(error("{" + base + R"(, "type": "orthographic", "view_width": 0})") ==
        "c.json: /camera/view_width: view_width must be positive");
  CHECK(error("{" + base + R"(, "type": "fisheye"})") ==
        "c.json: /camera/type: unknown camera type \"fisheye\" (known: perspective, orthographic)");
}
