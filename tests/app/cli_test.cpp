// The caustica executable end to end: renders, overrides, and bad input that must fail cleanly.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>
#include <nlohmann/json.hpp>
#include "core/accel.h"
#include "io/image_io.h"
#include "support/run.h"

using namespace caustica;
using test::run_caustica;
namespace fs = std::filesystem;

namespace {
const std::string kTiny = std::string(CAUSTICA_SOURCE_DIR) + "/tests/data/tiny.json";


}  // namespace

TEST_CASE("cli: renders a tiny scene to PNG and EXR", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  auto r = run_caustica("render '" + kTiny + "' -o out.png --quiet", dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  const Image png = read_image(dir.file("out.png"));
  CHECK(png.width == 32);
  CHECK(png.mean().x > 0.02f);
  r = run_caustica("render '" + kTiny + "' -o out.exr --spp 2 --width 20 --height 10 --threads 1 --seed 5", dir);
  REQUIRE(r.exit_code == 0);
  const Image exr = read_image(dir.file("out.exr"));
  CHECK(exr.width == 20);
  CHECK(exr.height == 10);
  CHECK(r.out.find("passes (spp): 2") != std::string::npos);
  CHECK(r.out.find("seed: 5") != std::string::npos);
  CHECK(r.out.find("rays per second") != std::string::npos);
}

TEST_CASE("cli: --version and --help", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  auto r = run_caustica("--version", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("caustica 0.") != std::string::npos);
  r = run_caustica("render --help", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("--spp") != std::string::npos);
}

TEST_CASE("cli: bad input exits non-zero with a located message and writes no image", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  dir.write("good.json", test::kLitFloorScene);
  struct Case {
    std::string name, scene_text, args, expect;
  };
  std::string good(test::kLitFloorScene);
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::vector<Case> cases = {
      {"malformed", "{\n  \"camera\": {\n    \"position\": [0, 1 3]\n", "", "bad.json:3:"},
      {"empty file", "", "", "bad.json:1:1:"},
      {"unknown material", replaced("\"material\": \"white\"", "\"material\": \"whit\""), "",
       "bad.json: /objects/0/material: unknown material \"whit\" (known: lamp, white)"},
      {"unknown key", replaced("\"fov\": 50", "\"fow\": 50"), "", "bad.json: /camera/fow: unknown key \"fow\""},
      {"missing mesh", replaced("{\"type\": \"quad\", \"origin\": [-2, 0, -2], \"edge1\": [0, 0, 4], \"edge2\": [4, 0, 0],",
                                "{\"type\": \"mesh\", \"file\": \"nowhere/bunny.obj\","),
       "", "mesh file not found: tried"},
      {"mesh path is a folder", replaced("{\"type\": \"quad\", \"origin\": [-2, 0, -2], \"edge1\": [0, 0, 4], \"edge2\": [4, 0, 0],",
                                         "{\"type\": \"mesh\", \"file\": \".\","),
       "", "not a regular file"},
      {"negative spp in scene", replaced("\"spp\": 2", "\"spp\": -1"), "", "bad.json: /render/spp: value -1 is out of range"},
      {"zero resolution", replaced("\"width\": 16", "\"width\": 0"), "", "/render/width"},
      {"huge resolution", replaced("\"width\": 16", "\"width\": 100000"), "", "/render/width"},
      {"zero radius", replaced("{\"type\": \"quad\", \"origin\": [-2, 0, -2], \"edge1\": [0, 0, 4], \"edge2\": [4, 0, 0],",
                               "{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0,"),
       "", "/objects/0/radius: radius must be positive"},
      {"wrong type", replaced("\"fov\": 50", "\"fov\": \"wide\""), "", "/camera/fov: expected a number"},
      {"infinite number", replaced("\"fov\": 50", "\"fov\": 1e999"), "", "bad.json:2:"},
      {"binary garbage", std::string("\x89PNG\r\n\x1a\n\x00\x01\xff", 11), "", "bad.json:1:1:"},
      {"truncated JSON", good.substr(0, good.size() / 2), "", "bad.json:"},
      {"NaN literal", replaced("\"fov\": 50", "\"fov\": NaN"), "", "bad.json:2:"},
      {"negative radius", replaced("{\"type\": \"quad\", \"origin\": [-2, 0, -2], \"edge1\": [0, 0, 4], \"edge2\": [4, 0, 0],",
                                   "{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": -1,"),
       "", "/objects/0/radius: radius must be positive"},
      {"zero-area light", replaced("{\"type\": \"quad\", \"origin\": [-0.5, 2, -0.5], \"edge1\": [1, 0, 0], \"edge2\": [0, 0, 1],",
                                   "{\"type\": \"triangle\", \"vertices\": [[0, 2, 0], [1, 2, 0], [2, 2, 0]],"),
       "", "/objects/1: emissive object has zero area"},
      {"IOR zero", replaced("\"white\": {\"type\": \"diffuse\", \"albedo\": [0.7, 0.7, 0.7]}",
                            "\"white\": {\"type\": \"glass\", \"ior\": 0}"),
       "", "/materials/white/ior: index of refraction must be positive"},
      {"missing texture", replaced("\"albedo\": [0.7, 0.7, 0.7]}", "\"reflectance\": {\"type\": \"bitmap\", \"filename\": \"wood.png\"}}"),
       "", "/materials/white/reflectance/filename: texture file not found: tried ./wood.png"},
      {"unreadable texture", replaced("\"albedo\": [0.7, 0.7, 0.7]}", "\"reflectance\": {\"type\": \"bitmap\", \"filename\": \"bad.json\"}}"),
       "", "/materials/white/reflectance/filename: ./bad.json: cannot read the texture"},
      {"unknown metal", replaced("\"white\": {\"type\": \"diffuse\", \"albedo\": [0.7, 0.7, 0.7]}",
                                 "\"white\": {\"type\": \"conductor\", \"material\": \"Gold\"}"),
       "", "unknown conductor \"Gold\" (known: none, a-C, Ag, Al, AlAs"},
      {"negative roughness", replaced("\"white\": {\"type\": \"diffuse\", \"albedo\": [0.7, 0.7, 0.7]}",
                                      "\"white\": {\"type\": \"roughconductor\", \"alpha\": -0.2}"),
       "", "/materials/white/alpha"},
      {"photons too many for memory", good, "--integrator photon --photons 2000000000", "GiB of memory"},
      {"--aov without a photon integrator", good, "--aov", "--aov needs a photon integrator"},
      {"negative --spp", good, "--spp -1", "--spp"},
      {"--threads 0", good, "--threads 0", "--threads"},
      {"unknown integrator", good, "--integrator phton", "error: unknown integrator \"phton\" (known: "},
      {"unknown integrator in the scene", replaced("\"objects\": [", "\"integrator\": {\"type\": \"frob\"},\n  \"objects\": ["), "",
       "bad.json: /integrator/type: unknown integrator \"frob\" (known: "},
      {"output in a missing folder", good, "-o missing/dir/out.png", "does not exist"},
      {"unknown output type", good, "-o out.jpeg", "unknown image type"},
      // Issue 23: keys given twice, and numbers that are not numbers or too large.
      {"a key given twice", replaced("\"fov\": 50", "\"fov\": 40, \"fov\": 170"), "",
       "bad.json: /camera: key \"fov\" is given twice"},
      {"a material defined twice", replaced("\"lamp\": {", "\"white\": {\"type\": \"diffuse\"}, \"lamp\": {"), "",
       "bad.json: /materials: key \"white\" is given twice"},
      {"a key twice in an array's object", replaced("\"material\": \"white\"}", "\"material\": \"white\", \"material\": \"lamp\"}"),
       "", "bad.json: /objects/0: key \"material\" is given twice"},
      {"--exposure nan", good, "--exposure nan", "expected a finite number, not nan"},
      {"--time nan", good, "--time nan", "expected a finite number, not nan"},
      {"--time inf", good, "--time inf", "expected a finite number, not inf"},
      {"--photons 1e30", good, "--integrator photon --photons 1e30", "--photons 1e30: out of range"},
      // Issue 23: a flag's value the integrator refuses is blamed on the flag, not on the scene file.
      {"--photons 1e10", good, "--integrator photon --photons 1e10",
       "error: --photons 10000000000: value 10000000000 is out of range [0, 2147483648]"},
      {"--gather-rays 1e10", good, "--integrator photon --gather-rays 1e10", "error: --gather-rays 10000000000: value"},
      {"--seed -1", good, "--seed -1", "--seed"},
      {"a seed of 2^64 in the scene", replaced("\"spp\": 2", "\"spp\": 2, \"seed\": 18446744073709551616"), "",
       "bad.json: /render/seed: expected a whole number from 0 to 2^64 - 1"},
      {"a negative seed in the scene", replaced("\"spp\": 2", "\"spp\": 2, \"seed\": -1"), "",
       "bad.json: /render/seed: expected a whole number from 0 to 2^64 - 1, found -1"},
      // Issue 23: positions and sizes where Embree would abort on the rays (beyond about 1.84e18).
      {"a camera at 2e18", replaced("\"position\": [0, 1, 3]", "\"position\": [0, 1, 2e18]"), "--integrator photon",
       "bad.json: /camera/position/2: coordinate 2e+18 is out of range: positions and sizes must lie within 1e+09 of the origin"},
      {"a camera at 1e30 (not \"up is parallel\")", replaced("\"position\": [0, 1, 3]", "\"position\": [0, 1, 1e30]"), "",
       "bad.json: /camera/position/2: coordinate 1e+30 is out of range"},
      {"a point light at 2e18", replaced("\"objects\": [", "\"lights\": [{\"type\": \"point\", \"position\": [2e18, 1, 0], \"intensity\": 1}],\n  \"objects\": ["),
       "--integrator photon", "bad.json: /lights/0/position/0: coordinate 2e+18 is out of range"},
      {"a focus distance of 1e30", replaced("\"fov\": 50", "\"fov\": 50, \"aperture_radius\": 0.1, \"focus_distance\": 1e30"), "",
       "bad.json: /camera/focus_distance: value 1e+30 is out of range [0, 1e+09]"},
      {"an aperture of 1e30", replaced("\"fov\": 50", "\"fov\": 50, \"aperture_radius\": 1e30, \"focus_distance\": 3"), "",
       "bad.json: /camera/aperture_radius: value 1e+30 is out of range [0, 1e+09]"},
      {"a sphere of radius 1e19", replaced("{\"type\": \"quad\", \"origin\": [-2, 0, -2], \"edge1\": [0, 0, 4], \"edge2\": [4, 0, 0],",
                                           "{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1e19,"),
       "--integrator photon", "bad.json: /objects/0: the object reaches 1e+19, which is out of range"},
      {"a mesh scaled past the range", replaced("{\"type\": \"quad\", \"origin\": [-2, 0, -2], \"edge1\": [0, 0, 4], \"edge2\": [4, 0, 0],",
                                                "{\"type\": \"mesh\", \"vertices\": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], \"indices\": [[0, 1, 2]], \"scale\": 1e18,"),
       "", "bad.json: /objects/0: the object reaches 1e+18, which is out of range"},
      // Issue 23: emission past what the film sums exactly rendered flat (1e15) or black (3e38).
      {"emission 1e15", replaced("\"emission\": [5, 5, 5]", "\"emission\": [1e15, 5, 5]"), "",
       "bad.json: /materials/lamp/emission/0: value 1e+15 is out of range [0, 1e+09]"},
      {"emission 3e38", replaced("\"emission\": [5, 5, 5]", "\"emission\": 3e38"), "--integrator photon",
       "bad.json: /materials/lamp/emission: value 3e+38 is out of range [0, 1e+09]"},
      // Issue 23: messages that misled.
      {"-D on a JSON scene", good, "-D rough=0.2", "bad.json: -D rough=... sets a parameter of a Mitsuba XML scene; this is a JSON scene"},
      {"a UTF-16 scene", std::string("\xFF\xFE{\0\n\0", 6), "",
       "bad.json: the file is encoded as UTF-16 or UTF-32; scene files must be UTF-8"},
  };
  for (const Case& c : cases) {
    SECTION(c.name) {
      dir.write("bad.json", c.scene_text);
      const std::string args = c.args.find("-o ") == std::string::npos ? c.args + " -o out.png" : c.args;
      const auto r = run_caustica("render bad.json " + args, dir);
      INFO("stderr: " << r.err);
      CHECK(r.exit_code != 0);
      CHECK(r.exit_code < 128);  // not killed by a signal
      CHECK(r.err.find(c.expect) != std::string::npos);
      fs::remove(dir.file("bad.json"));
      CHECK(test::no_images_left(dir));
    }
  }
}

TEST_CASE("cli: a scene scaled up to the coordinate bound renders as it does at scale 1, on both backends", "[app]" TIER_PROCESS) {
  // A diffuse floor and sphere under a directional light: their radiance does not depend on the
  // scene's scale. At 2.5e8 the camera stands at 7.5e8 and the floor reaches 5e8 (the bound is
  // 1e9); before the bound existed, 1e17 dropped the floor as "degenerate" and 2e18 aborted Embree.
  test::TempDir dir;
  auto scene = [](double s) {
    auto v = [s](double x, double y, double z) { return nlohmann::json::array({x * s, y * s, z * s}); };
    nlohmann::json j = {
        {"camera", {{"position", v(0, 1, 3)}, {"look_at", v(0, 0.5, 0)}, {"fov", 50}}},
        {"render", {{"width", 24}, {"height", 24}, {"spp", 4}}},
        {"materials", {{"white", {{"type", "diffuse"}, {"albedo", 0.7}}}}},
        {"objects",
         {{{"type", "quad"}, {"origin", v(-2, 0, -2)}, {"edge1", v(0, 0, 4)}, {"edge2", v(4, 0, 0)}, {"material", "white"}},
          {{"type", "sphere"}, {"center", v(0, 0.5, 0)}, {"radius", 0.5 * s}, {"material", "white"}}}},
        {"lights", {{{"type", "directional"}, {"direction", {0.3, -1, -0.4}}, {"irradiance", 2}}}}};
    return j.dump();
  };
  dir.write("one.json", scene(1.0));
  dir.write("big.json", scene(2.5e8));
  for (const std::string accel : {"bvh", "embree"}) {
    if (accel == "embree" && !embree_available()) continue;
    for (const std::string integrator : {"path", "photon"}) {
      INFO(accel << " " << integrator);
      for (const std::string name : {"one", "big"}) {
        const auto r = run_caustica("render " + name + ".json --accel " + accel + " --integrator " + integrator +
                                        " --threads 1 -o " + name + ".pfm -q",
                                    dir);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
      }
      const Image one = read_image(dir.file("one.pfm")), big = read_image(dir.file("big.pfm"));
      CHECK(one.mean().x > 0.1f);
      CHECK(big.mean().x == Approx(one.mean().x).epsilon(0.02));
      // Pixel by pixel too: the same random numbers at both scales.
      double diff = 0.0;
      for (size_t i = 0; i < one.pixels.size(); ++i) diff += std::abs(double(big.pixels[i].x) - one.pixels[i].x);
      CHECK(diff / one.pixels.size() < 0.05 * one.mean().x);
    }
  }
}

TEST_CASE("cli: under a memory limit, large allocations are refused with what they need", "[app]" TIER_PROCESS) {
  // Issue 23: these ended in "internal error: std::bad_alloc" (exit 2).
  if (!test::kAddressSpaceLimits) {
    WARN("skipped: ulimit -v cannot be used under AddressSanitizer");
    return;
  }
  test::TempDir dir;
  dir.write("scene.json", test::kLitFloorScene);
  auto r = run_caustica("render scene.json --width 16384 --height 16384 -o big.png", dir, test::address_space_limit(4 << 20));
  CHECK(r.exit_code == 1);
  // (The limit named is the tightest: ulimit -v here, unless the machine or its cgroup has less.)
  CHECK(r.err.find("error: a 16384 x 16384 image needs about 19.0 GiB of memory; ") != std::string::npos);
  CHECK(r.err.find(" leaves ") != std::string::npos);
  r = run_caustica("render scene.json --integrator photon --photons 30000000 --caustic-photons 100000 -o p.png", dir,
                   test::address_space_limit(2 << 20));
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("error: a photon pass of 30100000 photons needs about ") != std::string::npos);
  CHECK(r.err.find("GiB of memory; ") != std::string::npos);
  CHECK(test::no_images_left(dir));
  // The same limit leaves room for an ordinary render.
  r = run_caustica("render scene.json --integrator photon -o ok.png -q", dir, test::address_space_limit(2 << 20));
  CHECK(r.exit_code == 0);
}

TEST_CASE("cli: compare refuses an image that declares more pixels than it holds, a folder and a device", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  dir.write("big.pfm", "PF\n100000 100000\n-1.0\n" + std::string(1200, '\0'));
  Image ref(4, 2);
  write_image(dir.file("ref.pfm"), ref);
  auto r = run_caustica("compare big.pfm ref.pfm", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err == "error: big.pfm: the image declares 100000 x 100000 pixels, more than the file holds\n");
  fs::create_directory(dir.file("folder"));
  r = run_caustica("compare folder ref.pfm", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err == "error: folder: is a folder, not an image file\n");
  r = run_caustica("compare /dev/zero ref.pfm", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err == "error: /dev/zero: is not a regular file (a device or a pipe?), not an image file\n");
  r = run_caustica("compare nothing.pfm ref.pfm", dir);
  CHECK(r.err == "error: nothing.pfm: image file not found\n");
}

TEST_CASE("cli: compare refuses images with NaN or infinite pixels", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  Image ref(4, 2), img(4, 2);
  for (Color& c : ref.pixels) c = Color(0.5f);
  for (Color& c : img.pixels) c = Color(0.5f);
  img.at(3, 1) = Color(std::nanf(""), 0.5f, 0.5f);
  write_image(dir.file("img.exr"), img);
  write_image(dir.file("ref.exr"), ref);
  auto r = run_caustica("compare img.exr ref.exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("img.exr: 1 pixel is NaN or infinite, the first at (3, 1)") != std::string::npos);
  // The same as a reference, and an all-NaN image.
  r = run_caustica("compare ref.exr img.exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("img.exr: 1 pixel is NaN or infinite") != std::string::npos);
  for (Color& c : img.pixels) c = Color(std::numeric_limits<float>::infinity());
  write_image(dir.file("inf.exr"), img);
  r = run_caustica("compare inf.exr ref.exr --diff diff.png", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("inf.exr: 8 pixels are NaN or infinite") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.file("diff.png")));
  // Finite images still compare.
  r = run_caustica("compare ref.exr ref.exr", dir);
  CHECK(r.exit_code == 0);
}

TEST_CASE("cli: an unknown command and an empty list of integrators are named as such", "[app]" TIER_PROCESS) {
  // Issue 23: both were answered with what they were not ("A subcommand is required", "--time is required").
  test::TempDir dir;
  auto r = run_caustica("frobnicate", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err == "error: unknown command \"frobnicate\" (known: render, compare, converge, photons, plugins; see caustica --help)\n");
  dir.write("scene.json", test::kLitFloorScene);
  r = run_caustica("converge scene.json --integrators , --time 1 --reference ref.exr --out out", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("--integrators: expected integrator names (e.g. photon,path), not \"--time\"") != std::string::npos);
  r = run_caustica("converge scene.json --integrators path,phton --time 1 --reference ref.exr --out out", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("--integrators: unknown integrator \"phton\" (known: path, photon") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.file("out")));
}

TEST_CASE("cli: an environment map brighter than a scene may emit is refused", "[app]" TIER_PROCESS) {
  // Issue 23: an environment map of 3e38 rendered all black, with exit 0.
  test::TempDir dir;
  Image env(4, 2);
  for (Color& c : env.pixels) c = Color(0.5f);
  env.at(1, 1) = Color(3e38f, 1.0f, 1.0f);
  write_image(dir.file("sky.exr"), env);
  std::string scene(test::kLitFloorScene);
  scene.insert(scene.rfind('}'), R"(, "lights": [{"type": "envmap", "filename": "sky.exr"}])");
  dir.write("scene.json", scene);
  auto r = run_caustica("render scene.json -o out.png", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("scene.json: /lights/0/filename: environment map ./sky.exr is too bright: its brightest pixel is 3e+38, "
                   "the most a scene may emit is 1e9") != std::string::npos);
  fs::remove(dir.file("sky.exr"));
  CHECK(test::no_images_left(dir));
  env.at(1, 1) = Color(2.0f);
  write_image(dir.file("sky.exr"), env);
  r = run_caustica("render scene.json -o out.png -q", dir);
  CHECK(r.exit_code == 0);
}

TEST_CASE("cli: sampling_weight moves samples between lights, not the image's mean", "[app]" TIER_PROCESS) {
  // Issue 24: chosen in proportion to power times weight, each estimate divided by the choice's
  // probability: the same expectation in path and photon.
  test::TempDir dir;
  std::string scene(test::kLitFloorScene);
  const std::string lights = R"(, "lights": [{"type": "point", "position": [1, 1.5, 0.5], "intensity": 2},
    {"type": "point", "position": [-1, 1, 0], "intensity": 1W}])";
  auto with = [&](const std::string& weight) {
    std::string l = lights;
    l.replace(l.find('W'), 1, weight);
    std::string s = scene;
    s.insert(s.rfind('}'), l);
    return s;
  };
  dir.write("plain.json", with(""));
  dir.write("weighted.json", with(", \"sampling_weight\": 8"));
  for (const std::string integrator : {"path", "photon"}) {
    INFO(integrator);
    for (const std::string name : {"plain", "weighted"}) {
      const auto r = run_caustica("render " + name + ".json --integrator " + integrator + " --spp 64 -o " + name + ".pfm -q", dir);
      INFO(r.err);
      REQUIRE(r.exit_code == 0);
    }
    const double plain = read_image(dir.file("plain.pfm")).mean().x, weighted = read_image(dir.file("weighted.pfm")).mean().x;
    CHECK(plain > 0.05);
    CHECK(weighted == Approx(plain).epsilon(0.03));
  }
}

TEST_CASE("cli: a missing scene file and a folder as scene", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  auto r = run_caustica("render nothing.json -o out.png", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("nothing.json: scene file not found") != std::string::npos);
  r = run_caustica("render . -o out.png", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("is a directory") != std::string::npos);
}

TEST_CASE("cli: compare prints the figures, as JSON too, and writes an error map", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  Image ref(8, 8), img(8, 8);
  for (Color& c : ref.pixels) c = Color(0.5f);
  for (Color& c : img.pixels) c = Color(0.6f);
  write_image(dir.file("ref.exr"), ref);
  write_image(dir.file("img.exr"), img);
  auto r = run_caustica("compare img.exr ref.exr --diff diff.png", dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("rmse: 0.1") != std::string::npos);
  CHECK(fs::exists(dir.file("diff.png")));
  r = run_caustica("compare img.exr ref.exr --json", dir);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["rmse"].get<double>() == Approx(0.1).epsilon(1e-5));
  CHECK(j["mean_reference"][0].get<double>() == Approx(0.5));
  write_image(dir.file("small.exr"), Image(4, 8));
  r = run_caustica("compare small.exr ref.exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("small.exr is 4x8, ref.exr is 8x8") != std::string::npos);
  r = run_caustica("compare missing.exr ref.exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("missing.exr") != std::string::npos);
}

TEST_CASE("cli: compare against several references reports their floor and subtracts it", "[app]" TIER_PROCESS) {
  // Two references 0.4 and 0.6 (mean 0.5) and an image at 0.6: against the mean the error is
  // 0.1 per value; the references' spread says their mean is 0.1 off too (sample variance
  // 0.02, over 2), so the image's error without the floor is 0.
  test::TempDir dir;
  Image a(8, 8), b(8, 8), img(8, 8);
  for (Color& c : a.pixels) c = Color(0.4f);
  for (Color& c : b.pixels) c = Color(0.6f);
  for (Color& c : img.pixels) c = Color(0.6f);
  write_image(dir.file("a.exr"), a);
  write_image(dir.file("b.exr"), b);
  write_image(dir.file("img.exr"), img);
  const double relmse = 0.01 / (0.25 + 0.01);
  auto r = run_caustica("compare img.exr a.exr b.exr --json", dir);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["mean_reference"][0].get<double>() == Approx(0.5));
  CHECK(j["relmse"].get<double>() == Approx(relmse).epsilon(1e-5));
  CHECK(j["references"].get<int>() == 2);
  CHECK(j["reference_floor"].get<double>() == Approx(relmse).epsilon(1e-5));
  CHECK(j["relmse_floor_free"].get<double>() == Approx(0.0).margin(1e-6));
  r = run_caustica("compare img.exr a.exr b.exr", dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("reference floor: 0.0384") != std::string::npos);
  CHECK(r.out.find("relmse without the floor: ") != std::string::npos);
  // One reference: no floor in the figures.
  r = run_caustica("compare img.exr a.exr --json", dir);
  REQUIRE(r.exit_code == 0);
  CHECK_FALSE(nlohmann::json::parse(r.out).contains("reference_floor"));
  // The same file twice has no spread to estimate a floor from: a warning says so.
  r = run_caustica("compare img.exr a.exr a.exr", dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("do not differ, so their floor cannot be estimated") != std::string::npos);
  write_image(dir.file("small.exr"), Image(4, 8));
  r = run_caustica("compare img.exr a.exr small.exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("reference sizes differ: small.exr is 4x8, a.exr is 8x8") != std::string::npos);
}

TEST_CASE("cli: warnings (degenerate triangle, albedo above 1) still render", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  std::string text(test::kLitFloorScene);
  text.replace(text.find("\"albedo\": [0.7, 0.7, 0.7]"), 25, "\"albedo\": [1.2, 0.7, 0.7]");
  text.replace(text.find("\n  ]\n}"), 4,
               ", {\"type\": \"triangle\", \"vertices\": [[0, 0, 0], [1, 1, 1], [2, 2, 2]], \"material\": \"white\"}]");
  dir.write("warn.json", text);
  const auto r = run_caustica("render warn.json -o out.png -q", dir);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("warn.json: /objects/2: degenerate triangle (zero area) left out") != std::string::npos);
  CHECK(r.err.find("/materials/white/albedo: albedo above 1") != std::string::npos);
  CHECK(fs::exists(dir.file("out.png")));
}

TEST_CASE("cli: a signal during the photon pass stops it at once and writes no image", "[app][interrupt]" TIER_PROCESS) {
  // The pass used to go on normalising and indexing the photons traced so far (seconds for
  // millions) before the render noticed the stop.
  test::TempDir dir;
  const std::string scene = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-box.json";
  // The signal must come once the photon pass runs: in a sanitizer build on a loaded machine
  // the program's start took longer than 2 s (the default action then killed it, silently).
  // Wait three times as long as a small photon render takes, at least 2 s.
  auto t0 = std::chrono::steady_clock::now();
  REQUIRE(run_caustica("render '" + scene + "' --integrator photon --photons 1000 --spp 1 --width 8 --height 8 -q -o small.exr",
                       dir).exit_code == 0);
  const double delay = std::max(2.0, 3.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  fs::remove(dir.file("small.exr"));
  INFO("signal after " << delay << " s");
  t0 = std::chrono::steady_clock::now();
  // 20 million photons: a photon pass far longer than the delay before the signal.
  const auto r = run_caustica("render '" + scene + "' --integrator photon --photons 20000000 --width 32 --height 32 "
                              "--threads 2 -o out.exr", dir, "timeout --preserve-status -s INT " + std::to_string(delay) + " ");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  INFO(r.err << r.out);
  CHECK(r.exit_code == 130);
  CHECK(r.err.find("interrupted before the first pass was complete: no image written") != std::string::npos);
  CHECK(seconds < delay + 1.5);  // about 0.05 s after the signal in a Release build; was 2 s
  CHECK_FALSE(fs::exists(dir.file("out.exr")));
  CHECK(test::temporaries(dir.path()).empty());
}

TEST_CASE("cli: output names too long to write are refused before the render, AOV names too", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  const std::string scene = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-box.json";
  const std::string small = " --width 16 --height 16 --spp 2", photons = " --photons 2000 --caustic-photons 2000";
  // 256 bytes: one past NAME_MAX.
  auto r = run_caustica("render '" + scene + "'" + small + " -o " + std::string(252, 'a') + ".png", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("the file name is longer than 255 bytes") != std::string::npos);
  CHECK(r.out.find("render time") == std::string::npos);  // refused before rendering
  // The main image's name fits, its AOV's (stem + ".photons.exr", 258 bytes) does not: nothing is
  // rendered or written.
  const std::string stem(246, 'b');
  r = run_caustica("render '" + scene + "'" + small + photons + " --integrator photon --aov -o " + stem + ".exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find(stem + ".photons.exr: the file name is longer than 255 bytes") != std::string::npos);
  CHECK(r.out.find("render time") == std::string::npos);
  CHECK_FALSE(fs::exists(dir.file(stem + ".exr")));
  r = run_caustica("photons '" + scene + "' --width 16 --height 16" + photons + " -o " + std::string(252, 'c') + ".ply", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("the file name is longer than 255 bytes") != std::string::npos);
  CHECK(r.out.find("photons:") == std::string::npos);
}

TEST_CASE("cli: a signal while a file is written waits for it: the file complete, no temporary, exit 128 + signal", "[app][interrupt]" TIER_PROCESS) {
  // The signal is raised right after each output's temporary is made (a test hook in
  // io/atomic_file.cpp), the moment that killed photons and compare before: they left the
  // temporary and no file.
  test::TempDir dir;
  const std::string scene = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-box.json";
  const std::string small = " --width 16 --height 16 -q", photons = " --photons 2000 --caustic-photons 2000";
  const std::string hook = "CAUSTICA_TEST_SIGNAL_WHILE_WRITING=15 ";
  REQUIRE(run_caustica("render '" + scene + "'" + small + " --spp 2 -o ref.exr", dir).exit_code == 0);
  struct Case {
    std::string args;
    std::vector<std::string> files;
  };
  const std::vector<Case> cases = {
      {"render '" + scene + "'" + small + " --spp 2 -o r.png", {"r.png"}},
      {"render '" + scene + "'" + small + photons + " --spp 2 --integrator photon --aov -o a.exr",
       {"a.exr", "a.photons.exr", "a.radius.exr"}},
      {"photons '" + scene + "'" + small + photons + " -o p.png", {"p.png"}},
      {"photons '" + scene + "'" + small + photons + " -o p.ply", {"p.ply"}},
      {"compare ref.exr ref.exr --diff d.png", {"d.png"}},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const auto r = run_caustica(c.args, dir, hook);
    INFO(r.err << r.out);
    CHECK(r.exit_code == 143);
    for (const std::string& f : c.files) {
      INFO(f);
      REQUIRE(fs::exists(dir.file(f)));
      CHECK(fs::file_size(dir.file(f)) > 100);
      if (f.size() > 4 && f.substr(f.size() - 4) != ".ply") CHECK(read_image(dir.file(f)).width == 16);
    }
    CHECK(test::temporaries(dir.path()).empty());
  }
}

TEST_CASE("cli: an unreadable scene file is a clear error", "[app]" TIER_PROCESS) {
  test::TempDir dir;
  const std::string path = dir.write("locked.json", test::kLitFloorScene);
  fs::permissions(path, fs::perms::none);
  if (geteuid() == 0) {
    WARN("running as root: file permissions do not apply, unreadable-file case checked through a FIFO instead");
    fs::remove(path);
    REQUIRE(mkfifo(path.c_str(), 0600) == 0);
    const auto r = run_caustica("render locked.json -o out.png", dir);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("locked.json: not a regular file") != std::string::npos);
    return;
  }
  const auto r = run_caustica("render locked.json -o out.png", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("cannot open the scene file") != std::string::npos);
}

TEST_CASE("cli: Ctrl-C or SIGTERM stops a render within a second and keeps the completed passes", "[app][interrupt]" TIER_PROCESS) {
  // SIGTERM is what batch schedulers (Slurm) send at a job's time limit: handled as Ctrl-C.
  for (const auto& [signal, code] : {std::pair<std::string, int>{"INT", 130}, std::pair<std::string, int>{"TERM", 143}}) {
    INFO("SIG" << signal);
    test::TempDir dir;
    const std::string scene = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-box.json";
    const std::string args = "render '" + scene + "' --width 64 --height 64 --threads 2 -o out.exr";
    // The signal must come after the first group of passes is done, which in a sanitizer build on
    // a loaded machine took longer than 1.5 s (CI): wait twice as long as a 16-pass render takes.
    auto t0 = std::chrono::steady_clock::now();
    REQUIRE(run_caustica(args + " --spp 16 -q", dir).exit_code == 0);
    const double delay = std::max(1.5, 2.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    fs::remove(dir.file("out.exr"));
    INFO("signal after " << delay << " s");
    t0 = std::chrono::steady_clock::now();
    // A render that would take minutes.
    const auto r = run_caustica(args + " --spp 100000", dir,
                                "timeout --preserve-status -s " + signal + " " + std::to_string(delay) + " ");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    INFO(r.err << r.out);
    CHECK(r.exit_code == code);
    CHECK(seconds < delay + 3.0);  // generous for sanitizer builds; unstopped it would run for minutes
    CHECK(r.out.find("interrupted") != std::string::npos);
    const Image img = read_image(dir.file("out.exr"));
    CHECK(img.mean().x > 0.05f);  // the passes completed so far, not a black image
    CHECK(test::temporaries(dir.path()).empty());
  }
}
