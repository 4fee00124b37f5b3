// Mitsuba's .vol grid files: read back as written; every malformed file an error naming the
// file and what is wrong; random corruptions never crash the reader.
#include <catch2/catch.hpp>
#include <cstring>
#include "core/error.h"
#include "core/rng.h"
#include "io/volume_io.h"
#include "support/errors.h"

using namespace caustica;

namespace {
VolumeGrid small_grid(int channels) {
  VolumeGrid g;
  g.nx = 3, g.ny = 2, g.nz = 2, g.channels = channels;
  g.box.lo = Vec3(-1.0f, 0.0f, 2.0f);
  g.box.hi = Vec3(1.0f, 0.5f, 3.0f);
  for (int i = 0; i < 12 * channels; ++i) g.values.push_back(0.25f * float(i));
  return g;
}
std::string parse_error(const std::string& bytes) {
  return test::error_of([&] { parse_vol(bytes, "smoke.vol"); });
}
void put_int(std::string& b, size_t offset, int32_t v) { std::memcpy(&b[offset], &v, 4); }
void put_float(std::string& b, size_t offset, float v) { std::memcpy(&b[offset], &v, 4); }
}  // namespace

TEST_CASE("vol files: a grid reads back as written, one or three channels", "[io][media]") {
  for (int channels : {1, 3}) {
    const VolumeGrid g = small_grid(channels);
    const VolumeGrid r = parse_vol(format_vol(g), "smoke.vol");
    CHECK(r.nx == 3);
    CHECK(r.ny == 2);
    CHECK(r.nz == 2);
    CHECK(r.channels == channels);
    CHECK(r.box.lo == g.box.lo);
    CHECK(r.box.hi == g.box.hi);
    CHECK(r.values == g.values);
  }
}

TEST_CASE("vol files: malformed ones are errors naming the file and the fault", "[io][media]") {
  const std::string good = format_vol(small_grid(1));
  CHECK(parse_error(good).empty());
  CHECK_THAT(parse_error("PLY\x03"), Catch::Contains("smoke.vol") && Catch::Contains("\"VOL\""));
  std::string b = good;
  b[3] = 2;
  CHECK_THAT(parse_error(b), Catch::Contains("version 2"));
  CHECK_THAT(parse_error(good.substr(0, 30)), Catch::Contains("truncated") && Catch::Contains("header"));
  b = good;
  put_int(b, 4, 3);
  CHECK_THAT(parse_error(b), Catch::Contains("encoding 3"));
  b = good;
  put_int(b, 12, 0);
  CHECK_THAT(parse_error(b), Catch::Contains("at least 1"));
  b = good;
  put_int(b, 20, 2);
  CHECK_THAT(parse_error(b), Catch::Contains("2 channels"));
  b = good;
  put_float(b, 24, 5.0f);  // x from 5 to 1
  CHECK_THAT(parse_error(b), Catch::Contains("bounding box") && Catch::Contains("axis 0"));
  // The header lies about the size: more voxels than the file holds, and fewer.
  b = good;
  put_int(b, 8, 4);
  CHECK_THAT(parse_error(b), Catch::Contains("the header says 4 x 2 x 2") && Catch::Contains("truncated"));
  CHECK_THAT(parse_error(good.substr(0, good.size() - 4)), Catch::Contains("truncated"));
  CHECK_THAT(parse_error(good + "xxxx"), Catch::Contains("the file has"));
  b = good;
  put_int(b, 8, 1 << 12), put_int(b, 12, 1 << 12), put_int(b, 16, 1 << 12);
  CHECK_THAT(parse_error(b), Catch::Contains("more than"));
  // Voxels that are not finite or are negative, named by their place.
  b = good;
  put_float(b, 48 + 4 * 7, std::nanf(""));
  CHECK_THAT(parse_error(b), Catch::Contains("voxel (1, 0, 1)") && Catch::Contains("finite"));
  b = good;
  put_float(b, 48, -0.5f);
  CHECK_THAT(parse_error(b), Catch::Contains("voxel (0, 0, 0)") && Catch::Contains("-0.5"));
  CHECK_THAT(test::error_of([] { read_vol_file("/nonexistent/smoke.vol"); }), Catch::Contains("/nonexistent/smoke.vol"));
}

TEST_CASE("vol files: corrupted and truncated files never crash the reader (fuzz)", "[io][media][fuzz]") {
  const std::string good = format_vol(small_grid(3));
  Rng rng(17);
  int errors = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string b = good;
    const int edits = 1 + int(rng.next_float() * 4.0f);
    for (int e = 0; e < edits; ++e) b[size_t(rng.next_float() * float(b.size())) % b.size()] = char(rng.next_u32() & 0xff);
    if (rng.next_float() < 0.3f) b.resize(size_t(rng.next_float() * float(b.size())));
    try {
      const VolumeGrid g = parse_vol(b, "fuzz.vol");
      REQUIRE(g.values.size() == size_t(g.nx) * size_t(g.ny) * size_t(g.nz) * size_t(g.channels));
    } catch (const InputError&) {
      ++errors;
    }
  }
  CHECK(errors > 1000);  // (most corruptions are caught; the rest are valid grids)
}
