// `caustica photons` (PNG splats, heat map, PLY point cloud) and `render --aov`.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cstring>
#include <filesystem>
#include "io/image_io.h"
#include "support/run.h"

using namespace caustica;
namespace fs = std::filesystem;

namespace {
const std::string kTiny = std::string(CAUSTICA_SOURCE_DIR) + "/tests/data/tiny.json";
}

TEST_CASE("photons: a PLY point cloud with one vertex per photon", "[app][photons]" TIER_PROCESS) {
  test::TempDir dir;
  const auto r = test::run_caustica("photons '" + kTiny + "' --photons 3000 --map global -o maps.ply", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string ply = test::read_text(dir.file("maps.ply"));
  REQUIRE(ply.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);
  const size_t at = ply.find("element vertex ");
  REQUIRE(at != std::string::npos);
  const long n = std::stol(ply.substr(at + 15));
  CHECK(n >= 3000);
  CHECK(r.out.find("photons: " + std::to_string(n) + " in global map") != std::string::npos);
  const size_t body = ply.find("end_header\n") + 11;
  REQUIRE(ply.size() - body == size_t(n) * 27);  // 6 floats + 3 bytes per vertex
  // Every point lies inside the unit box of tiny.json and has a unit normal.
  for (long i = 0; i < n; i += 97) {
    float v[6];
    std::memcpy(v, ply.data() + body + size_t(i) * 27, sizeof v);
    for (int k = 0; k < 3; ++k) CHECK((v[k] >= -1e-3f && v[k] <= 1.001f));
    CHECK(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] == Approx(1.0f).epsilon(0.02));
  }
}

TEST_CASE("photons: PNG splats and heat map show photons over the dimmed scene", "[app][photons]" TIER_PROCESS) {
  test::TempDir dir;
  auto r = test::run_caustica("photons '" + kTiny + "' --photons 20000 -o maps.png", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("visible from the camera: ") != std::string::npos);
  const Image splats = read_image(dir.file("maps.png"));
  r = test::run_caustica("photons '" + kTiny + "' --photons 20000 --heatmap -o heat.png", dir);
  REQUIRE(r.exit_code == 0);
  const Image heat = read_image(dir.file("heat.png"));
  CHECK(splats.width == 32);
  CHECK(splats.mean().x > 0.05f);
  CHECK(heat.pixels != splats.pixels);
  r = test::run_caustica("photons '" + kTiny + "' -o maps.jpg", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("must be .png or .ply") != std::string::npos);
}

TEST_CASE("render --aov: photon counts and radii beside the image", "[app][photons]" TIER_PROCESS) {
  test::TempDir dir;
  const auto r = test::run_caustica("render '" + kTiny + "' --integrator photon --photons 20000 --gather-rays 4 "
                                    "--spp 2 --aov -o out.exr -q",
                                    dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const Image count = read_image(dir.file("out.photons.exr"));
  const Image radius = read_image(dir.file("out.radius.exr"));
  CHECK(count.width == 32);
  // Every pixel sees a diffuse wall: the global estimate used photons (at most k = 50).
  float lo = 1e9f, hi = 0;
  for (const Color& c : count.pixels) {
    lo = std::min(lo, c.r);
    hi = std::max(hi, c.r);
  }
  CHECK(lo > 0.0f);
  CHECK(hi <= 50.0f);
  CHECK(radius.mean().r > 0.0f);
  CHECK(radius.mean().r < 1.0f);  // the box is 1 wide
}
