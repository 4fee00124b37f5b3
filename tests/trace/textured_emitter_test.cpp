// Textured area emitters (Mitsuba's area emitter with a bitmap radiance): seen directly, a texture
// at the image's resolution with filter_type nearest comes back texel for texel; its light
// reaches a floor as the texture's mean over the surface, in the path tracer and in photons.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/lights/area.h"
#include "core/textures/bitmap.h"
#include "io/image_io.h"
#include "support/render_util.h"
#include "support/temp_dir.h"

using namespace caustica;

namespace {
// An 8 x 8 texture of distinct values, red from its column, green from its row.
Image texel_grid() {
  Image img(8, 8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) img.at(x, y) = Color(0.1f + 0.25f * float(x), 0.05f + 0.5f * float(y), 1.0f / float(1 + x + y));
  }
  return img;
}

// A square [-1, 1]^2 in z = 0 facing +z whose UVs put the texture upright as seen from +z.
const char* kSquareObj = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
}  // namespace

TEST_CASE("textured area emitter: seen at the texture's resolution, nearest filtering returns every texel",
          "[trace][light][texture]" TIER_UNIT) {
  test::TempDir dir;
  const Image tex = texel_grid();
  write_image(dir.file("tex.exr"), tex);
  dir.write("square.obj", kSquareObj);
  // The camera 1 unit in front with a 90-degree field of view: the square fills the 8 x 8 image,
  // one pixel per texel; 1 sample per pixel with the box filter lands inside its texel.
  const std::string scene = R"({
    "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0], "fov": 90},
    "materials": {"lamp": {"type": "diffuse", "reflectance": 0,
      "emission": {"type": "bitmap", "filename": "tex.exr", "filter_type": "nearest"}}},
    "objects": [{"type": "mesh", "file": "square.obj", "material": "lamp"}]})";
  for (uint64_t seed : {1, 2, 3}) {
    const auto r = test::render_text(scene, "path", "{}", 1, 8, 8, seed, 0, dir.path().string());
    for (int y = 0; y < 8; ++y) {
      for (int x = 0; x < 8; ++x) {
        for (int c = 0; c < 3; ++c) {
          INFO("seed " << seed << " pixel " << x << ", " << y << " channel " << c);
          CHECK(r.image.at(x, y)[c] == Approx(tex.at(x, y)[c]).epsilon(1e-5));
        }
      }
    }
  }
}

TEST_CASE("bitmap: bilinear filtering is the interpolation between the four nearest texel centres",
          "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  const Image tex = texel_grid();
  write_image(dir.file("tex.exr"), tex);
  const BitmapTexture t(dir.file("tex.exr"), TextureFilter::Bilinear, TextureWrap::Clamp, UvTransform{}, false);
  for (int i = 0; i < 200; ++i) {
    // Points between texel centres (the clamped border is left out).
    const float u = (0.5f + 7.0f * float((i * 37) % 200) / 200.0f) / 8.0f;
    const float v = (0.5f + 7.0f * float((i * 91) % 200) / 200.0f) / 8.0f;
    const float fx = u * 8.0f - 0.5f, fy = v * 8.0f - 0.5f;
    const int x0 = std::min(6, int(fx)), y0 = std::min(6, int(fy));
    const float a = fx - float(x0), b = fy - float(y0);
    const Color expected = (1 - a) * (1 - b) * tex.at(x0, y0) + a * (1 - b) * tex.at(x0 + 1, y0) +
                           (1 - a) * b * tex.at(x0, y0 + 1) + a * b * tex.at(x0 + 1, y0 + 1);
    const Color got = t.eval(Vec2(u, v));
    for (int c = 0; c < 3; ++c) {
      INFO("uv " << u << ", " << v << " channel " << c);
      CHECK(got[c] == Approx(expected[c]).epsilon(1e-4));
    }
  }
}

TEST_CASE("textured area emitter: power is the texture's mean, the floor it lights agrees in path and photon",
          "[trace][light][texture]" TIER_UNIT) {
  test::TempDir dir;
  // Left half 4, right half 0: the light's power is that of a uniform radiance of 2.
  Image half(2, 1);
  half.at(0, 0) = Color(4.0f);
  half.at(1, 0) = Color(0.0f);
  write_image(dir.file("half.exr"), half);
  // The square 2 units above the floor, facing down.
  dir.write("lamp.obj", "v -1 2 -1\nv 1 2 -1\nv 1 2 1\nv -1 2 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  auto scene_with = [](const std::string& emission) {
    return R"({
      "camera": {"position": [0, 6, 0.01], "look_at": [0, 0, 0], "fov": 60},
      "materials": {"floor": {"type": "diffuse", "reflectance": 0.5},
                    "lamp": {"type": "diffuse", "reflectance": 0, "emission": )" + emission + R"(}},
      "objects": [{"type": "quad", "origin": [-4, 0, -4], "edge1": [0, 0, 8], "edge2": [8, 0, 0], "material": "floor"},
                  {"type": "mesh", "file": "lamp.obj", "material": "lamp"}]})";
  };
  const std::string textured = scene_with(R"({"type": "bitmap", "filename": "half.exr", "filter_type": "nearest"})");
  LoadedScene s = parse_scene(textured, "t.json", dir.path().string());
  REQUIRE(s.scene->lights.size() == 1);
  const auto* area = dynamic_cast<const AreaLight*>(s.scene->lights[0].get());
  REQUIRE(area);
  CHECK(area->textured());
  // pi A mean(Le), A = 4; the mean is estimated on a 128 x 128 grid of points by area.
  CHECK(area->power().x == Approx(kPi * 4.0 * 2.0).epsilon(0.01));

  const auto path = test::render_text(textured, "path", "{}", 64, 32, 32, 1, 0, dir.path().string());
  const auto photon = test::render_text(textured, "photon", "{}", 16, 32, 32, 1, 0, dir.path().string());
  const Color mp = path.image.mean(), mq = photon.image.mean();
  INFO("path " << mp.x << ", photon " << mq.x);
  CHECK(mp.x > 0.01f);
  CHECK(mq.x == Approx(mp.x).epsilon(0.03));
  // Half the floor is lit more than the other: the lit side is the texture's bright half.
  float left = 0, right = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 16; ++x) {
      left += path.image.at(x, y).x;
      right += path.image.at(31 - x, y).x;
    }
  }
  CHECK(std::max(left, right) > 1.5f * std::min(left, right));
}
