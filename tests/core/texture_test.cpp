// Textures and surface parameterisations: checkerboard and to_uv, bitmaps through
// OpenImageIO's TextureSystem (orientation, wrap modes, sRGB), sphere UVs, OBJ vt/vn,
// face_normals, and the errors for missing or unreadable texture files.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <OpenImageIO/imageio.h>
#include <vector>
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "core/textures/bitmap.h"
#include "core/textures/checkerboard.h"
#include "support/temp_dir.h"
#include "core/rng.h"
#include "core/math.h"

using namespace caustica;
using Catch::Matchers::Contains;

TEST_CASE("checkerboard: color0 where u and v fall in the same half, to_uv scales and shifts", "[core][texture]" TIER_UNIT) {
  const CheckerboardTexture plain(Color(1, 0, 0), Color(0, 0, 1), UvTransform{});
  CHECK(plain.eval(Vec2(0.75f, 0.75f)) == plain.eval(Vec2(0.25f, 0.25f)));
  CHECK(plain.eval(Vec2(0.75f, 0.25f)) != plain.eval(Vec2(0.25f, 0.25f)));
  CHECK(plain.eval(Vec2(1.25f, 0.25f)) == plain.eval(Vec2(0.25f, 0.25f)));  // periodic
  UvTransform four;
  four.m00 = four.m11 = 4.0f;
  const CheckerboardTexture tiled(Color(1, 0, 0), Color(0, 0, 1), four);
  CHECK(tiled.eval(Vec2(0.0625f, 0.0625f)) == plain.eval(Vec2(0.25f, 0.25f)));
  CHECK(tiled.eval(Vec2(0.1875f, 0.0625f)) == plain.eval(Vec2(0.75f, 0.25f)));
}

TEST_CASE("checkerboard: Mitsuba's colours, color0 where (u > 1/2) == (v > 1/2)", "[core][texture]" TIER_UNIT) {
  const CheckerboardTexture t(Color(1, 0, 0), Color(0, 0, 1), UvTransform{});
  CHECK(t.eval(Vec2(0.25f, 0.25f)) == Color(1, 0, 0));
  CHECK(t.eval(Vec2(0.75f, 0.75f)) == Color(1, 0, 0));
  CHECK(t.eval(Vec2(0.75f, 0.25f)) == Color(0, 0, 1));
}

TEST_CASE("bitmap: (0, 0) is the top-left pixel, repeat, mirror and clamp wrap as named", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  Image img(4, 2);  // top row: 0.1, 0.2, 0.3, 0.4; bottom row: 0.5 .. 0.8 (red channel)
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) img.at(x, y) = Color(0.1f * float(1 + x + 4 * y), 0.0f, 1.0f);
  }
  const std::string path = dir.file("t.exr");
  write_image(path, img);
  const BitmapTexture nearest(path, TextureFilter::Nearest, TextureWrap::Repeat, UvTransform{}, false);
  CHECK(nearest.width() == 4);
  CHECK(nearest.eval(Vec2(0.125f, 0.25f)).x == Approx(0.1f));  // top-left pixel centre
  CHECK(nearest.eval(Vec2(0.875f, 0.75f)).x == Approx(0.8f));  // bottom-right
  CHECK(nearest.eval(Vec2(1.125f, 0.25f)).x == Approx(0.1f));  // repeat
  const BitmapTexture mirror(path, TextureFilter::Nearest, TextureWrap::Mirror, UvTransform{}, false);
  CHECK(mirror.eval(Vec2(1.125f, 0.25f)).x == Approx(0.4f));
  const BitmapTexture clamp(path, TextureFilter::Nearest, TextureWrap::Clamp, UvTransform{}, false);
  CHECK(clamp.eval(Vec2(1.6f, 0.25f)).x == Approx(0.4f));
  CHECK(clamp.eval(Vec2(-0.6f, 0.75f)).x == Approx(0.5f));
  // Bilinear halfway between the first two pixel centres of the top row.
  const BitmapTexture bilinear(path, TextureFilter::Bilinear, TextureWrap::Clamp, UvTransform{}, false);
  CHECK(bilinear.eval(Vec2(0.25f, 0.25f)).x == Approx(0.15f).margin(1e-4));
  CHECK(bilinear.eval(Vec2(0.25f, 0.25f)).z == Approx(1.0f).margin(1e-4));
}

TEST_CASE("bitmap: 8-bit images are decoded from sRGB unless raw", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  Image img(1, 1);
  img.pixels[0] = Color(0.5f);  // written as sRGB 8-bit: linear 0.5 -> 188/255 -> read back 0.5
  const std::string path = dir.file("grey.png");
  write_image(path, img);
  const BitmapTexture decoded(path, TextureFilter::Nearest, TextureWrap::Repeat, UvTransform{}, false);
  CHECK(decoded.eval(Vec2(0.5f)).x == Approx(0.5f).margin(0.01f));
  const BitmapTexture raw(path, TextureFilter::Nearest, TextureWrap::Repeat, UvTransform{}, true);
  CHECK(raw.eval(Vec2(0.5f)).x == Approx(188.0f / 255.0f).margin(0.01f));
}

namespace {
// An 8-bit PNG of 2 x 1 pixels with `channels` channels, the last of them alpha.
std::string write_png_with_alpha(const test::TempDir& dir, const std::string& name, int channels,
                                 const std::vector<unsigned char>& texels) {
  const std::string path = dir.file(name);
  auto out = OIIO::ImageOutput::create(path);
  REQUIRE(out);
  OIIO::ImageSpec spec(2, 1, channels, OIIO::TypeDesc::UINT8);
  spec.alpha_channel = channels - 1;
  spec.attribute("oiio:UnassociatedAlpha", 1);  // the colour is stored as given
  REQUIRE(out->open(path, spec));
  REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, texels.data()));
  REQUIRE(out->close());
  return path;
}
}  // namespace

TEST_CASE("bitmap: alpha is dropped, grey-alpha reads as grey and RGBA as RGB, colour not multiplied by alpha",
          "[core][texture]" TIER_UNIT) {
  // Mitsuba's leaf mask (docs/scenes/bsdf_mask_after.xml) is grey-alpha: grey was read as red and
  // alpha as green, so the mask's opacity came out about half everywhere.
  test::TempDir dir;
  // Grey 255 and 0, alpha 255 and 64.
  const std::string ya = write_png_with_alpha(dir, "ya.png", 2, {255, 255, 0, 64});
  const BitmapTexture grey(ya, TextureFilter::Nearest, TextureWrap::Clamp, UvTransform{}, true);
  CHECK(grey.eval(Vec2(0.25f, 0.5f)) == Color(1.0f));
  CHECK(grey.eval(Vec2(0.75f, 0.5f)) == Color(0.0f));
  // RGBA: (255, 128, 0) at alpha 64 stays (255, 128, 0), raw.
  const std::string rgba = write_png_with_alpha(dir, "rgba.png", 4, {255, 128, 0, 64, 0, 0, 255, 255});
  const BitmapTexture colour(rgba, TextureFilter::Nearest, TextureWrap::Clamp, UvTransform{}, true);
  const Color c = colour.eval(Vec2(0.25f, 0.5f));
  CHECK(c.x == Approx(1.0f).margin(1e-3));
  CHECK(c.y == Approx(128.0f / 255.0f).margin(1e-3));
  CHECK(c.z == Approx(0.0f).margin(1e-3));
  CHECK(colour.eval(Vec2(0.75f, 0.5f)) == Color(0.0f, 0.0f, 1.0f));
}

namespace {
LoadedScene load(const test::TempDir& dir, const std::string& objects, const std::string& materials) {
  const std::string text = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]},
    "materials": )" + materials + R"(, "objects": )" + objects + R"(,
    "lights": [{"type": "point", "position": [0, 3, -3], "intensity": 1}]})";
  return parse_scene(text, dir.file("s.json"), dir.path().string());
}
const char* kWhite = R"({"white": {"type": "diffuse"}})";
}  // namespace

TEST_CASE("sphere UVs: u = phi / 2 pi around z, v = theta / pi from +z", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  LoadedScene s = load(dir, R"([{"type": "sphere", "center": [1, 2, 3], "radius": 2, "material": "white"}])", kWhite);
  SurfaceHit hit;
  REQUIRE(s.scene->intersect(Ray{Vec3(1, 2, 10), Vec3(0, 0, -1)}, hit));  // the +z pole
  CHECK(hit.sp.uv.y == Approx(0.0f).margin(1e-3));
  REQUIRE(s.scene->intersect(Ray{Vec3(10, 2, 3), Vec3(-1, 0, 0)}, hit));  // +x on the equator
  CHECK(hit.sp.uv.x == Approx(0.0f).margin(1e-3));
  CHECK(hit.sp.uv.y == Approx(0.5f).margin(1e-3));
  REQUIRE(s.scene->intersect(Ray{Vec3(1, 10, 3), Vec3(0, -1, 0)}, hit));  // +y: phi = 90 degrees
  CHECK(hit.sp.uv.x == Approx(0.25f).margin(1e-3));
}

TEST_CASE("OBJ: vt becomes (u, 1 - v), vn is interpolated, face_normals turns it off", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  // A unit square in the z = 0 plane facing -z, with normals bent outwards along x.
  dir.write("sq.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                      "vn -0.6 0 -0.8\nvn 0.6 0 -0.8\nvn 0.6 0 -0.8\nvn -0.6 0 -0.8\n"
                      "f 1/1/1 4/4/4 3/3/3\nf 1/1/1 3/3/3 2/2/2\n");
  LoadedScene s = load(dir, R"([{"type": "mesh", "file": "sq.obj", "material": "white"}])", kWhite);
  SurfaceHit hit;
  REQUIRE(s.scene->intersect(Ray{Vec3(0.25f, 0.75f, -1), Vec3(0, 0, 1)}, hit));
  CHECK(hit.sp.uv.x == Approx(0.25f).margin(1e-4));
  CHECK(hit.sp.uv.y == Approx(0.25f).margin(1e-4));  // OBJ v = 0.75 is near the image's top
  CHECK(hit.n.z == Approx(-1.0f));                    // geometric normal from the winding
  // Halfway between x = 0 (nx -0.6) and x = 1 (nx 0.6) at x = 0.25: nx = -0.3, normalised.
  const Vec3 expected = glm::normalize(Vec3(-0.3f, 0.0f, -0.8f));
  CHECK(hit.frame.n.x == Approx(expected.x).margin(1e-4));
  CHECK(hit.frame.n.z == Approx(expected.z).margin(1e-4));

  LoadedScene flat = load(dir, R"([{"type": "mesh", "file": "sq.obj", "material": "white", "face_normals": true}])", kWhite);
  REQUIRE(flat.scene->intersect(Ray{Vec3(0.25f, 0.75f, -1), Vec3(0, 0, 1)}, hit));
  CHECK(hit.frame.n.z == Approx(-1.0f));
  CHECK(hit.sp.uv.y == Approx(0.25f).margin(1e-4));  // UVs stay
}

TEST_CASE("quads carry UVs along their edges, a textured material reads them", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  LoadedScene s = load(dir, R"([{"type": "quad", "origin": [0, 0, 0], "edge1": [2, 0, 0], "edge2": [0, 4, 0], "material": "check"}])",
                       R"({"check": {"type": "diffuse", "reflectance": {"type": "checkerboard", "color0": [0.8, 0, 0], "color1": [0, 0, 0.8]}}})");
  SurfaceHit hit;
  REQUIRE(s.scene->intersect(Ray{Vec3(0.5f, 3.0f, -1), Vec3(0, 0, 1)}, hit));
  CHECK(hit.sp.uv.x == Approx(0.25f).margin(1e-4));
  CHECK(hit.sp.uv.y == Approx(0.75f).margin(1e-4));
  CHECK(hit.material->albedo(hit.sp) == Color(0, 0, 0.8f));
  REQUIRE(s.scene->intersect(Ray{Vec3(1.5f, 3.0f, -1), Vec3(0, 0, 1)}, hit));
  CHECK(hit.material->albedo(hit.sp) == Color(0.8f, 0, 0));
}

TEST_CASE("textures: missing and unreadable files, unknown types and keys are errors", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  const std::string quad = R"([{"type": "quad", "origin": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "m"}])";
  auto with = [&](const std::string& tex) {
    return load(dir, quad, R"({"m": {"type": "diffuse", "reflectance": )" + tex + "}}");
  };
  CHECK_THROWS_WITH(with(R"({"type": "bitmap", "filename": "nope.png"})"),
                    Contains("/materials/m/reflectance/filename") && Contains("tried") && Contains("nope.png"));
  dir.write("garbage.png", "this is not a png");
  CHECK_THROWS_WITH(with(R"({"type": "bitmap", "filename": "garbage.png"})"),
                    Contains("/materials/m/reflectance/filename") && Contains("garbage.png"));
  CHECK_THROWS_WITH(with(R"({"type": "noise"})"), Contains("unknown texture type \"noise\"") && Contains("checkerboard"));
  CHECK_THROWS_WITH(with(R"({"type": "checkerboard", "colour0": 1})"), Contains("/materials/m/reflectance/colour0"));
  CHECK_THROWS_WITH(with(R"({"type": "checkerboard", "to_uv": {"scale": [1, 2, 3]}})"), Contains("to_uv/scale"));
  // Issue 23: decoded and checked once at load. A NaN texel (a correct-looking EXR) and a PNG cut
  // short (its header intact) are errors naming the file, not black texels at render time.
  Image nan_texels(4, 2);
  for (Color& c : nan_texels.pixels) c = Color(0.5f);
  nan_texels.at(2, 1) = Color(0.5f, std::nanf(""), 0.5f);
  write_image(dir.file("nan.exr"), nan_texels);
  CHECK_THROWS_WITH(with(R"({"type": "bitmap", "filename": "nan.exr"})"),
                    Contains("/materials/m/reflectance/filename") && Contains("nan.exr: NaN or infinite texel at (2, 1)"));
  // Past the 1e9 a colour may hold (an emission texture of 1e15 rendered a flat or black image).
  nan_texels.at(2, 1) = Color(0.5f);
  nan_texels.at(3, 0) = Color(0.5f, 0.5f, 1e15f);
  write_image(dir.file("bright.exr"), nan_texels);
  CHECK_THROWS_WITH(with(R"({"type": "bitmap", "filename": "bright.exr"})"),
                    Contains("/materials/m/reflectance/filename") &&
                        Contains("bright.exr: the texel at (3, 0) is 1e+15, beyond the 1e+09 a colour may hold"));
  Image noise(64, 64);
  uint32_t s = 7;
  for (Color& c : noise.pixels) {
    s = s * 1664525u + 1013904223u;
    c = Color(float(s >> 8) / float(1u << 24), 0.5f, 0.25f);
  }
  write_image(dir.file("whole.png"), noise);
  const std::string png = test::read_text(dir.file("whole.png"));
  dir.write("cut.png", png.substr(0, png.size() / 2));
  CHECK_NOTHROW(with(R"({"type": "bitmap", "filename": "whole.png"})"));
  CHECK_THROWS_WITH(with(R"({"type": "bitmap", "filename": "cut.png"})"),
                    Contains("/materials/m/reflectance/filename") && Contains("cut.png: cannot decode the texture"));
  dir.write("bad.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK_THROWS_WITH(load(dir, R"([{"type": "mesh", "file": "bad.obj", "material": "white"}])", kWhite),
                    Contains("bad.obj:1") && Contains("\"nan\" is not a finite number"));
}

TEST_CASE("shading frames follow dp/du: along phi on spheres, along edge1 on quads", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  LoadedScene s = load(dir, R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"},
                                {"type": "quad", "origin": [5, -1, 0], "edge1": [0, 2, 0], "edge2": [2, 0, 0], "material": "white"}])", kWhite);
  SurfaceHit hit;
  REQUIRE(s.scene->intersect(Ray{Vec3(10, 0, 0), Vec3(-1, 0, 0)}, hit));  // +x on the sphere's equator
  CHECK(std::abs(hit.frame.s.y) == Approx(1.0f).margin(1e-5));              // phi grows towards +y
  CHECK(glm::dot(hit.frame.s, hit.frame.n) == Approx(0.0f).margin(1e-5));
  REQUIRE(s.scene->intersect(Ray{Vec3(5.5f, 0, -3), Vec3(0, 0, 1)}, hit));
  CHECK(hit.frame.s.y == Approx(1.0f).margin(1e-5));  // edge1 runs along +y
  CHECK(std::abs(hit.frame.t.x) == Approx(1.0f).margin(1e-5));
}

TEST_CASE("bitmap: the gradient is the bilinear lookup's derivative, through sRGB decoding and to_uv", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  Image img(5, 3);
  Rng rng(17);
  for (Color& c : img.pixels) c = Color(rng.next_float(), rng.next_float(), rng.next_float());
  for (const char* name : {"g.exr", "g.png"}) {  // linear floats, and 8-bit sRGB
    const std::string path = dir.file(name);
    write_image(path, img);
    UvTransform rotated;
    rotated.m00 = 0.6f, rotated.m01 = -0.8f, rotated.m10 = 0.8f, rotated.m11 = 0.6f, rotated.tx = 0.1f;
    for (const UvTransform& to_uv : {UvTransform{}, rotated}) {
      const BitmapTexture t(path, TextureFilter::Bilinear, TextureWrap::Repeat, to_uv, false);
      auto value = [&](const Vec2& uv) { return double(luminance(t.eval(uv))); };
      int checked = 0;
      for (int i = 0; i < 400 && checked < 60; ++i) {
        const Vec2 uv(rng.next_float(), rng.next_float());
        // Away from the lines through texel centres, where the bilinear lookup has kinks.
        const Vec2 st = to_uv.apply(uv);
        const float fx = st.x * 5.0f - 0.5f, fy = st.y * 3.0f - 0.5f;
        const float dx = fx - std::floor(fx), dy = fy - std::floor(fy);
        if (dx < 0.1f || dx > 0.9f || dy < 0.1f || dy > 0.9f) continue;
        Vec2 g;
        REQUIRE(t.gradient(uv, g));
        constexpr float h = 1e-3f;
        const double du = (value(uv + Vec2(h, 0)) - value(uv - Vec2(h, 0))) / (2 * h);
        const double dv = (value(uv + Vec2(0, h)) - value(uv - Vec2(0, h))) / (2 * h);
        INFO(name << " uv " << uv.x << ", " << uv.y);
        CHECK(g.x == Approx(du).margin(0.02 + 0.01 * std::abs(du)));
        CHECK(g.y == Approx(dv).margin(0.02 + 0.01 * std::abs(dv)));
        ++checked;
      }
      CHECK(checked >= 30);
    }
  }
  // A nearest lookup is constant between texels: gradient zero, as Mitsuba's.
  const BitmapTexture nearest(dir.file("g.exr"), TextureFilter::Nearest, TextureWrap::Repeat, UvTransform{}, false);
  Vec2 g(1.0f);
  REQUIRE(nearest.gradient(Vec2(0.3f, 0.4f), g));
  CHECK(g == Vec2(0.0f));
}

TEST_CASE("textures: bitmaps of one file share its texels; a file rewritten is read again", "[core][texture]" TIER_UNIT) {
  test::TempDir dir;
  const std::string quad = R"([{"type": "quad", "origin": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "a"},
      {"type": "quad", "origin": [3, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "b"}])";
  const std::string materials = R"({"a": {"type": "diffuse", "reflectance": {"type": "bitmap", "filename": "t.pfm"}},
      "b": {"type": "diffuse", "reflectance": {"type": "bitmap", "filename": "t.pfm", "filter_type": "nearest"}}})";
  Image img(2, 2);
  for (Color& c : img.pixels) c = Color(0.25f);
  write_image(dir.file("t.pfm"), img);
  const LoadedScene first = load(dir, quad, materials);
  std::vector<const BitmapTexture*> bitmaps;
  for (const auto& t : first.scene->textures) bitmaps.push_back(dynamic_cast<const BitmapTexture*>(t.get()));
  REQUIRE(bitmaps.size() == 2);
  REQUIRE(bitmaps[0] != nullptr);
  REQUIRE(bitmaps[1] != nullptr);
  CHECK(bitmaps[0]->shares_texels_with(*bitmaps[1]));
  // The file rewritten (same size, another time) while the first scene lives: read again.
  for (Color& c : img.pixels) c = Color(0.75f);
  write_image(dir.file("t.pfm"), img);
  const LoadedScene second = load(dir, quad, materials);
  const auto* again = dynamic_cast<const BitmapTexture*>(second.scene->textures[0].get());
  REQUIRE(again != nullptr);
  CHECK_FALSE(again->shares_texels_with(*bitmaps[0]));
  CHECK(again->eval(Vec2(0.5f)) == Color(0.75f));
  CHECK(bitmaps[0]->eval(Vec2(0.5f)) == Color(0.25f));
}
