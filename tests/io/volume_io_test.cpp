// Grid files (Mitsuba's .vol, OpenVDB's .vdb): read back as written; every malformed file an error naming the
// file and what is wrong; random corruptions never crash the reader.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include "core/error.h"
#include "core/rng.h"
#include "io/vdb_io.h"
#include "io/volume_io.h"
#include "support/grids.h"
#include "support/temp_dir.h"
#include "support/errors.h"
#include "support/random.h"

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

TEST_CASE("vol files: a grid reads back as written, one or three channels", "[io][media]" TIER_UNIT) {
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

TEST_CASE("vol files: malformed ones are errors naming the file and the fault", "[io][media]" TIER_UNIT) {
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

TEST_CASE("vol files: corrupted and truncated files never crash the reader (fuzz)", "[io][media][fuzz]" TIER_UNIT) {
  const std::string good = format_vol(small_grid(3));
  Rng rng(17);
  int errors = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::string b = test::corrupt(good, rng, 0.3f);
    try {
      // Half as densities, half as an SDF grid's signed values.
      const bool signed_values = i % 2 == 1;
      const VolumeGrid g = parse_vol(b, "fuzz.vol", signed_values);
      REQUIRE(g.values.size() == size_t(g.nx) * size_t(g.ny) * size_t(g.nz) * size_t(g.channels));
      for (float v : g.values) REQUIRE((std::isfinite(v) && (signed_values || v >= 0.0f)));
    } catch (const InputError&) {
      ++errors;
    }
  }
  CHECK(errors > 1000);  // (most corruptions are caught; the rest are valid grids)
}

namespace {
// A 5 x 4 x 6 grid of densities in [0.1, 2) (none zero: every voxel active in a .vdb).
VolumeGrid dense_grid() {
  Rng rng(41);
  return test::make_grid(5, 4, 6, Vec3(-1.0f, 0.0f, 0.5f), Vec3(2.0f, 1.0f, 3.0f),
                         [&](int, int, int) { return 0.1f + 1.9f * rng.next_float(); });
}
std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace

TEST_CASE("vdb files: an OpenVDB grid reads back as the same volume in world space; a .vol and a .vdb are told "
          "apart by their bytes; wrong grids and files are errors naming the file",
          "[io][media]" TIER_UNIT) {
  if (!vdb_supported()) {
    WARN("built without OpenVDB: .vdb files are errors");
    CHECK_THAT(test::error_of([] { read_vdb_file("smoke.vdb", ""); }), Catch::Contains("smoke.vdb") && Catch::Contains("OpenVDB"));
    return;
  }
  test::TempDir dir;
  const VolumeGrid g = dense_grid();
  write_vdb_file(dir.file("smoke.vdb"), g, "density");
  const VolumeGrid r = read_grid_file(dir.file("smoke.vdb"), "");
  // One voxel of background around the active ones.
  CHECK(r.nx == g.nx + 2);
  CHECK(r.ny == g.ny + 2);
  CHECK(r.nz == g.nz + 2);
  CHECK(r.channels == 1);
  const GridVolume original(g), read(r);
  Rng rng(43);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
    const Vec3 p = g.box.lo + u * g.box.extent();
    INFO("at " << p.x << " " << p.y << " " << p.z);
    REQUIRE(read.eval(p).x == Approx(original.eval(p).x).epsilon(1e-4).margin(1e-5));
  }
  // Beyond the box the density falls to the background within one voxel (0.75 wide in x).
  CHECK(read.eval(Vec3(2.0f + 0.75f, 0.5f, 1.5f)).x == Approx(0.0f).margin(1e-5));
  CHECK(read.eval(Vec3(2.0f + 0.375f, 0.5f, 1.5f)).x ==
        Approx(0.5f * original.eval(Vec3(2.0f, 0.5f, 1.5f)).x).epsilon(1e-4));
  CHECK(read.max_value() == Approx(original.max_value()));
  // By name; a name the file lacks lists the ones it has.
  CHECK(read_grid_file(dir.file("smoke.vdb"), "density").nx == g.nx + 2);
  CHECK_THAT(test::error_of([&] { read_grid_file(dir.file("smoke.vdb"), "temperature"); }),
             Catch::Contains("smoke.vdb") && Catch::Contains("no grid named \"temperature\"") && Catch::Contains("density"));
  // A .vol under any name is read as one; a grid name there is an error.
  const std::string vol = dir.write("smoke.vdb.vol", format_vol(g));
  CHECK(read_grid_file(vol, "").values == g.values);
  CHECK_THAT(test::error_of([&] { read_grid_file(vol, "density"); }), Catch::Contains("OpenVDB"));
  // A negative density is named by its voxel (index space).
  VolumeGrid bad = g;
  bad.values[size_t((2 * g.ny + 1) * g.nx + 3)] = -0.5f;
  write_vdb_file(dir.file("bad.vdb"), bad, "density");
  CHECK_THAT(test::error_of([&] { read_grid_file(dir.file("bad.vdb"), ""); }),
             Catch::Contains("bad.vdb") && Catch::Contains("voxel (3, 1, 2)") && Catch::Contains("-0.5"));
  // Truncated files: an error each, never a crash.
  const std::string bytes = read_bytes(dir.file("smoke.vdb"));
  REQUIRE(bytes.size() > 100);
  for (size_t cut : {size_t(4), size_t(8), size_t(40), bytes.size() / 3, bytes.size() / 2, bytes.size() - 10}) {
    INFO("cut at " << cut);
    const std::string path = dir.write("cut.vdb", bytes.substr(0, cut));
    CHECK_THAT(test::error_of([&] { read_grid_file(path, ""); }), Catch::Contains("cut.vdb"));
  }
}

TEST_CASE("vdb files: corrupted and truncated files never crash or hang the reader (fuzz)", "[io][media][fuzz]" TIER_UNIT) {
  if (!vdb_supported()) return;
  test::TempDir dir;
  write_vdb_file(dir.file("good.vdb"), dense_grid(), "density");
  const std::string good = read_bytes(dir.file("good.vdb"));
  const std::string path = dir.file("fuzz.vdb");
  Rng rng(47);
  int errors = 0, read = 0;
  for (int i = 0; i < 400; ++i) {
    const std::string b = test::corrupt(good, rng, 0.2f);
    std::ofstream(path, std::ios::binary) << b;
    try {
      const VolumeGrid g = read_grid_file(path, "");
      REQUIRE(g.values.size() == size_t(g.nx) * size_t(g.ny) * size_t(g.nz) * size_t(g.channels));
      ++read;
    } catch (const InputError& e) {
      REQUIRE_THAT(e.what(), Catch::Contains("fuzz.vdb"));
      ++errors;
    }
  }
  CHECK(errors > 200);  // (most corruptions are caught; the rest are valid grids)
  CHECK(read > 0);
}
