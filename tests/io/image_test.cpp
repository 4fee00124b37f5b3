// Image files (io/image_io.h): round trips through EXR, PFM and PNG, exposure, output-path checks, atomic
// writes (no temporary left behind) and unreadable inputs.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <filesystem>
#include "io/image_io.h"
#include "io/json_reader.h"
#include "core/rng.h"
#include "support/temp_dir.h"

using namespace caustica;
using Catch::Matchers::Contains;

namespace {
// A non-square image whose pixels all differ, so flips and transposes show.
Image test_image(int w, int h, float lo, float hi, uint64_t seed) {
  Image img(w, h);
  Rng rng(seed);
  for (Color& c : img.pixels) c = Color(lo + (hi - lo) * rng.next_float(), lo + (hi - lo) * rng.next_float(), lo + (hi - lo) * rng.next_float());
  return img;
}

double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// Files in `dir` that look like write_image's temporaries (".<stem>.tmp...").
std::vector<std::string> leftovers(const std::filesystem::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp") != std::string::npos || (!name.empty() && name[0] == '.')) found.push_back(name);
  }
  return found;
}
}  // namespace

namespace {
void check_exact_round_trip(const std::vector<std::string>& names) {
  test::TempDir dir;
  // Linear formats keep negatives, values above 1 and tiny values.
  Image img = test_image(7, 5, -2.0f, 50.0f, 1);
  img.at(0, 0) = Color(0.0f, 1e-6f, 12345.678f);
  img.at(6, 4) = Color(0.1f, 0.2f, 0.3f);
  for (const std::string& name : names) {
    INFO(name);
    const std::string path = dir.file(name);
    write_image(path, img);
    const Image back = read_image(path);
    REQUIRE(back.width == 7);
    REQUIRE(back.height == 5);
    int differing = 0;
    for (size_t i = 0; i < img.pixels.size(); ++i) differing += back.pixels[i] != img.pixels[i];
    CHECK(differing == 0);
    CHECK(back.at(6, 4) == Color(0.1f, 0.2f, 0.3f));
    CHECK(back.at(0, 0) == Color(0.0f, 1e-6f, 12345.678f));
  }
  CHECK(leftovers(dir.path()).empty());
}
}  // namespace

TEST_CASE("image: EXR round trip is exact", "[core][image]" TIER_UNIT) {
  check_exact_round_trip({"a.exr", "UPPER.EXR"});
  test::TempDir dir;
  const Image img = test_image(7, 5, -2.0f, 50.0f, 1);
  // Exposure applies to PNG only.
  write_image(dir.file("exposed.exr"), img, 1.0f);
  CHECK(read_image(dir.file("exposed.exr")).pixels == img.pixels);
}

// Regression: OpenImageIO 2.4 (Debian 12) has no PFM writer; PFM is written by hand.
TEST_CASE("image: PFM round trip is exact", "[core][regression]" TIER_UNIT) { check_exact_round_trip({"a.pfm"}); }

TEST_CASE("image: a hand-written PFM reads exactly, bottom row first", "[core][image]" TIER_UNIT) {
  test::TempDir dir;
  // PFM: "PF", width height, scale (negative: little endian), rows from the bottom up.
  std::string pfm = "PF\n3 2\n-1.0\n";
  const float rows[2][3][3] = {{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}},                     // bottom row (y = 1)
                               {{-1.5f, 0.25f, 1e-7f}, {100, 200, 300}, {0, 0, 0.5f}}};  // top row (y = 0)
  for (const auto& row : rows) {
    for (const auto& px : row) pfm.append(reinterpret_cast<const char*>(px), sizeof(px));
  }
  const Image img = read_image(dir.write("hand.pfm", pfm));
  REQUIRE(img.width == 3);
  REQUIRE(img.height == 2);
  CHECK(img.at(0, 0) == Color(-1.5f, 0.25f, 1e-7f));
  CHECK(img.at(2, 0) == Color(0, 0, 0.5f));
  CHECK(img.at(0, 1) == Color(1, 2, 3));
  CHECK(img.at(2, 1) == Color(7, 8, 9));
}

TEST_CASE("image: HDR round trip keeps about 1% precision", "[core][image]" TIER_UNIT) {
  test::TempDir dir;
  const Image img = test_image(6, 4, 0.01f, 20.0f, 2);
  write_image(dir.file("a.hdr"), img);
  const Image back = read_image(dir.file("a.hdr"));
  REQUIRE(back.width == 6);
  REQUIRE(back.height == 4);
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      // RGBE keeps 8 mantissa bits for the largest component of a pixel.
      REQUIRE(std::abs(back.pixels[i][c] - img.pixels[i][c]) <= max_component(img.pixels[i]) / 128.0f);
    }
  }
}

TEST_CASE("image: PNG round trip within one sRGB step", "[core][image]" TIER_UNIT) {
  test::TempDir dir;
  Image img = test_image(9, 3, 0.0f, 1.0f, 3);
  img.at(0, 0) = Color(0.0f, 1.0f, 0.5f);
  img.at(1, 0) = Color(0.001f, 0.0031308f, 0.99f);
  write_image(dir.file("a.png"), img);
  const Image back = read_image(dir.file("a.png"));
  REQUIRE(back.width == 9);
  REQUIRE(back.height == 3);
  int off = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      // Encoded, the value is rounded to the nearest of 255 steps.
      const double encoded = linear_to_srgb(img.pixels[i][c]);
      const double back_encoded = linear_to_srgb(back.pixels[i][c]);
      off += std::abs(back_encoded - encoded) > 0.5 / 255 + 1e-5;
      // Decoded, it is the sRGB decoding of that step.
      off += std::abs(back.pixels[i][c] - srgb_decode(std::round(255 * encoded) / 255)) > 1e-5;
    }
  }
  CHECK(off == 0);
  CHECK(back.at(0, 0).r == 0.0f);
  CHECK(back.at(0, 0).g == Approx(1.0f).margin(1e-6));
  CHECK(back.at(0, 0).b == Approx(0.5f).margin(0.005f));
  // Out-of-range values clamp to black and white.
  Image clamp(2, 1);
  clamp.at(0, 0) = Color(-1.0f, 2.0f, 1e9f);
  clamp.at(1, 0) = Color(std::nanf(""), 0.0f, kInfinity);
  write_image(dir.file("clamp.png"), clamp);
  const Image cb = read_image(dir.file("clamp.png"));
  CHECK(cb.at(0, 0) == Color(0.0f, 1.0f, 1.0f));
  CHECK(cb.at(1, 0) == Color(0.0f, 0.0f, 1.0f));
  CHECK(leftovers(dir.path()).empty());
}

TEST_CASE("image: PNG exposure +1 stop doubles the linear value", "[core][image]" TIER_UNIT) {
  test::TempDir dir;
  Image img(4, 1);
  const float values[4] = {0.05f, 0.1f, 0.2f, 0.4f};
  for (int x = 0; x < 4; ++x) img.at(x, 0) = Color(values[x]);
  write_image(dir.file("plain.png"), img, 0.0f);
  write_image(dir.file("up.png"), img, 1.0f);
  write_image(dir.file("down.png"), img, -2.0f);
  const Image plain = read_image(dir.file("plain.png")), up = read_image(dir.file("up.png")),
              down = read_image(dir.file("down.png"));
  for (int x = 0; x < 4; ++x) {
    INFO("value " << values[x]);
    // Compare after encoding, where the 8-bit rounding is at most half a step.
    CHECK(std::abs(linear_to_srgb(up.at(x, 0).r) - linear_to_srgb(2.0f * values[x])) <= 0.5f / 255 + 1e-5f);
    CHECK(std::abs(linear_to_srgb(down.at(x, 0).g) - linear_to_srgb(0.25f * values[x])) <= 0.5f / 255 + 1e-5f);
    CHECK(up.at(x, 0).r == Approx(2.0f * plain.at(x, 0).r).epsilon(0.03));
  }
  // The brightest value at +1 stop is 0.8, not clamped.
  CHECK(up.at(3, 0).b == Approx(0.8f).margin(0.005f));
}

TEST_CASE("image: check_output_path", "[core][image]" TIER_UNIT) {
  test::TempDir dir;
  CHECK(is_supported_image_path("x.exr"));
  CHECK(is_supported_image_path("dir/x.PNG"));
  CHECK_FALSE(is_supported_image_path("x.bmp"));
  CHECK_FALSE(is_supported_image_path("x"));
  REQUIRE_NOTHROW(check_output_path(dir.file("ok.exr")));
  const std::string missing = (dir.path() / "no-such-folder" / "x.exr").string();
  REQUIRE_THROWS_AS(check_output_path(missing), InputError);
  REQUIRE_THROWS_WITH(check_output_path(missing), Contains(missing) && Contains("does not exist"));
  REQUIRE_THROWS_AS(check_output_path(dir.file("x.bmp")), InputError);
  REQUIRE_THROWS_WITH(check_output_path(dir.file("x.bmp")), Contains("unknown image type \".bmp\"") && Contains(".exr"));
  REQUIRE_THROWS_AS(check_output_path(dir.file("noext")), InputError);
  // A folder with a supported name is not a file.
  std::filesystem::create_directory(dir.path() / "folder.png");
  REQUIRE_THROWS_WITH(check_output_path(dir.file("folder.png")), Contains("directory"));
  // write_image checks too, and leaves nothing behind.
  REQUIRE_THROWS_AS(write_image(missing, Image(2, 2)), InputError);
  REQUIRE_THROWS_AS(write_image(dir.file("x.bmp"), Image(2, 2)), InputError);
  CHECK(leftovers(dir.path()).empty());
  CHECK_FALSE(std::filesystem::exists(dir.file("x.bmp")));
}

TEST_CASE("image: writing replaces an existing file and leaves no temporary", "[core][image]" TIER_UNIT) {
  test::TempDir dir;
  const std::string path = dir.file("out.exr");
  write_image(path, test_image(3, 3, 0, 1, 4));
  Image second(5, 2);
  second.at(4, 1) = Color(7.0f);
  write_image(path, second);
  const Image back = read_image(path);
  CHECK(back.width == 5);
  CHECK(back.at(4, 1) == Color(7.0f));
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  CHECK(files == 1);
  CHECK(leftovers(dir.path()).empty());
}

TEST_CASE("image: unreadable files are input errors", "[core][image]" TIER_UNIT) {
  test::TempDir dir;
  REQUIRE_THROWS_AS(read_image(dir.file("missing.exr")), InputError);
  REQUIRE_THROWS_WITH(read_image(dir.file("missing.exr")), Contains("missing.exr"));
  Rng rng(5);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = char(rng.next_u32() & 0xff);
  for (const char* name : {"x.png", "x.exr", "x.pfm", "x.hdr"}) {
    INFO(name);
    const std::string path = dir.write(name, garbage);
    REQUIRE_THROWS_AS(read_image(path), InputError);
    REQUIRE_THROWS_WITH(read_image(path), Contains(name));
  }
  // Empty and truncated files.
  REQUIRE_THROWS_AS(read_image(dir.write("empty.png", "")), InputError);
  write_image(dir.file("whole.png"), test_image(16, 16, 0, 1, 6));
  const std::string png = test::read_text(dir.file("whole.png"));
  REQUIRE_THROWS_AS(read_image(dir.write("half.png", png.substr(0, png.size() / 2))), InputError);
  // A folder is not an image.
  REQUIRE_THROWS_AS(read_image(dir.path().string()), InputError);
}

TEST_CASE("image: mean", "[core][image]" TIER_UNIT) {
  Image img(2, 2);
  img.at(0, 0) = Color(1, 2, 3);
  img.at(1, 1) = Color(3, 2, 1);
  CHECK(img.mean() == Color(1, 1, 1));
  CHECK(Image().mean() == Color(0.0f));
  CHECK(linear_to_srgb(0.0031308f) == Approx(0.04045f).margin(1e-5));
  CHECK(linear_to_srgb(0.5f) == Approx(0.735357f).margin(1e-5));
}
