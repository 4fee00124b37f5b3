// Scene loading: a valid scene's contents, and every class of error named by file, line and
// column (syntax) or JSON pointer (meaning). Also loads every scene shipped in scenes/.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <filesystem>
#include <limits>
#include "core/lights/area.h"
#include "io/json_reader.h"
#include "io/scene_loader.h"
#include "support/temp_dir.h"

using namespace caustica;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {
const char* kMaterials = R"({
    "white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
    "light": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "emission": [1, 2, 3]},
    "glass": {"type": "glass", "ior": 1.5}
  })";

// A scene with the given objects (and optionally other materials and a render block).
std::string scene_text(const std::string& objects, const std::string& materials = kMaterials,
                       const std::string& render = R"({"width": 8, "height": 8, "spp": 1})") {
  return R"({
  "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
  "render": )" + render + R"(,
  "materials": )" + materials + R"(,
  "objects": )" + objects + "\n}";
}

const std::string kSphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"})";
const std::string kLightQuad =
    R"({"type": "quad", "origin": [0, 2, 0], "edge1": [2, 0, 0], "edge2": [0, 0, 3], "material": "light"})";

LoadedScene parse(const std::string& text, const std::string& base_dir = ".") {
  return parse_scene(text, "test.json", base_dir);
}
}  // namespace

TEST_CASE("scene loader: a minimal valid scene", "[core][scene_loader]" TIER_UNIT) {
  const std::string objects = "[" + kSphere + ",\n" + kLightQuad + R"(,
    {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "glass"},
    {"type": "mesh", "vertices": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], "indices": [[0, 1, 2], [0, 2, 3]], "material": "white"}
  ])";
  LoadedScene loaded = parse(scene_text(objects));
  REQUIRE(loaded.scene);
  const Scene& scene = *loaded.scene;
  CHECK(loaded.sphere_count == 1);
  CHECK(loaded.triangle_count == 2 + 1 + 2);  // quad -> 2, triangle, mesh -> 2
  CHECK(loaded.warnings.empty());
  CHECK(scene.accel().primitives().size() == 6);
  CHECK(scene.materials.size() == 3);
  CHECK(scene.render.width == 8);
  CHECK(scene.render.spp == 1);
  CHECK(scene.render.max_depth == RenderSettings{}.max_depth);  // default kept
  REQUIRE(scene.lights.size() == 1);
  const auto* area = dynamic_cast<const AreaLight*>(scene.lights[0].get());
  REQUIRE(area != nullptr);
  // The emissive quad of area 2 x 3 becomes one area light with power pi A Le.
  CHECK(area->area() == Approx(6.0f));
  CHECK(area->power().r == Approx(kPi * 6.0f * 1.0f));
  CHECK(area->power().g == Approx(kPi * 6.0f * 2.0f));
  CHECK(area->power().b == Approx(kPi * 6.0f * 3.0f));
  // Both quad triangles point at the light, the others at none.
  int light_prims = 0;
  for (const Primitive& p : scene.accel().primitives()) light_prims += p.light == 0;
  CHECK(light_prims == 2);
  // The camera looks at the origin: the ray through the image centre hits the unit sphere at t = 4.
  SurfaceHit hit;
  REQUIRE(scene.intersect(scene.camera.generate_ray(4.0f, 4.0f), hit));
  CHECK(hit.t == Approx(4.0f).epsilon(1e-4));
}

TEST_CASE("scene loader: point lights and a scene without lights", "[core][scene_loader]" TIER_UNIT) {
  std::string text = scene_text("[" + kSphere + "]");
  LoadedScene dark = parse(text);
  CHECK(dark.scene->lights.empty());
  REQUIRE(dark.warnings.size() == 1);
  CHECK_THAT(dark.warnings[0], Contains("no lights"));

  text.insert(text.rfind('}'), R"(, "lights": [{"type": "point", "position": [0, 3, 0], "intensity": [2, 2, 2]}])");
  LoadedScene lit = parse(text);
  REQUIRE(lit.scene->lights.size() == 1);
  CHECK(lit.scene->lights[0]->is_delta());
  CHECK(lit.scene->lights[0]->power().r == Approx(4 * kPi * 2));
}

TEST_CASE("scene loader: a syntax error names file, line and column", "[core][scene_loader]" TIER_UNIT) {
  // Line 3 lacks a comma between two numbers; the parser stops at the second one, column 22.
  const std::string text =
      "{\n"
      "  \"camera\": {\"position\": [0, 0, -5],\n"
      "    \"look_at\": [0, 0 0], \"fov\": 40},\n"
      "  \"materials\": {}, \"objects\": []\n"
      "}\n";
  REQUIRE(text.find("0 0]") + 2 - text.find("    \"look_at\"") + 1 == 22);
  REQUIRE_THROWS_AS(parse(text), InputError);
  REQUIRE_THROWS_WITH(parse(text), StartsWith("test.json:3:22: "));
  REQUIRE_THROWS_WITH(parse(text), Contains("\"look_at\": [0, 0 0]") && Contains("\n  " + std::string(21, ' ') + "^"));

  // A missing comma between two objects on line 3: the unexpected '{' is at column 14.
  const std::string objects = "{\n  \"objects\": [\n    {\"a\": 1} {\"b\": 2}\n  ]\n}";
  REQUIRE_THROWS_WITH(parse(objects), StartsWith("test.json:3:14: "));
  // Truncated file: the error is at the end.
  REQUIRE_THROWS_WITH(parse("{\n  \"camera\": {\n"), StartsWith("test.json:3:1: "));
}

TEST_CASE("scene loader: unknown material lists the known ones", "[core][scene_loader]" TIER_UNIT) {
  const std::string text = scene_text(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glas"}])");
  REQUIRE_THROWS_AS(parse(text), InputError);
  REQUIRE_THROWS_WITH(parse(text), StartsWith("test.json: /objects/0/material: unknown material \"glas\" (known: "));
  REQUIRE_THROWS_WITH(parse(text), Contains("(known: glass, light, white)"));
}

TEST_CASE("scene loader: semantic errors name the JSON pointer", "[core][scene_loader]" TIER_UNIT) {
  SECTION("misspelt key") {
    const std::string text = scene_text(R"([{"type": "sphere", "center": [0, 0, 0], "radious": 1, "material": "white"}])");
    REQUIRE_THROWS_AS(parse(text), InputError);
    REQUIRE_THROWS_WITH(parse(text), Contains("test.json: /objects/0/radious: ") && Contains("unknown key"));
  }
  SECTION("unknown key at the top level and in the camera") {
    std::string text = scene_text("[" + kSphere + "]");
    text.insert(text.rfind('}'), R"(, "light": [])");
    REQUIRE_THROWS_WITH(parse(text), Contains("test.json: /light: unknown key"));
    std::string cam = scene_text("[" + kSphere + "]");
    cam.replace(cam.find("\"fov\""), 5, "\"fovy\"");
    REQUIRE_THROWS_WITH(parse(cam), Contains("/camera/fovy: unknown key \"fovy\""));
  }
  SECTION("negative spp") {
    const std::string text = scene_text("[" + kSphere + "]", kMaterials, R"({"spp": -4})");
    REQUIRE_THROWS_AS(parse(text), InputError);
    REQUIRE_THROWS_WITH(parse(text), Contains("test.json: /render/spp: ") && Contains("-4"));
  }
  SECTION("fractional spp") {
    REQUIRE_THROWS_WITH(parse(scene_text("[" + kSphere + "]", kMaterials, R"({"spp": 2.5})")),
                        Contains("/render/spp: expected an integer"));
  }
  SECTION("zero and negative radius") {
    for (const char* radius : {"0", "-1"}) {
      const std::string text = scene_text(std::string(R"([{"type": "sphere", "center": [0, 0, 0], "radius": )") + radius +
                                          R"(, "material": "white"}])");
      REQUIRE_THROWS_AS(parse(text), InputError);
      REQUIRE_THROWS_WITH(parse(text), Contains("test.json: /objects/0/radius: radius must be positive"));
    }
  }
  SECTION("index of refraction not positive") {
    for (const char* ior : {"0", "-1.5"}) {
      const std::string mats = std::string(R"({"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
        "glass": {"type": "glass", "ior": )") + ior + "}}";
      REQUIRE_THROWS_WITH(parse(scene_text("[" + kSphere + "]", mats)),
                          Contains("test.json: /materials/glass/ior: ") && Contains("positive"));
    }
  }
  SECTION("vec3 of the wrong length and wrong types") {
    REQUIRE_THROWS_WITH(parse(scene_text(R"([{"type": "sphere", "center": [0, 0], "radius": 1, "material": "white"}])")),
                        Contains("/objects/0/center: expected an array of 3 numbers"));
    REQUIRE_THROWS_WITH(parse(scene_text(R"([{"type": "sphere", "center": [0, "1", 0], "radius": 1, "material": "white"}])")),
                        Contains("/objects/0/center/1: expected a number"));
  }
  SECTION("unknown object type and missing key") {
    REQUIRE_THROWS_WITH(parse(scene_text(R"([{"type": "cube", "material": "white"}])")),
                        Contains("/objects/0/type: unknown object type \"cube\""));
    REQUIRE_THROWS_WITH(parse(scene_text(R"([{"type": "sphere", "center": [0, 0, 0], "material": "white"}])")),
                        Contains("/objects/0: missing required key \"radius\""));
  }
  SECTION("mesh index out of range") {
    REQUIRE_THROWS_WITH(parse(scene_text(R"([{"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                                            "indices": [[0, 1, 3]], "material": "white"}])")),
                        Contains("/objects/0/indices/0/2: "));
  }
  SECTION("negative colour component") {
    const std::string mats = R"({"white": {"type": "diffuse", "albedo": [0.5, -0.1, 0.5]}})";
    REQUIRE_THROWS_WITH(parse(scene_text("[" + kSphere + "]", mats)), Contains("/materials/white/albedo/1: "));
  }
}

TEST_CASE("scene loader: numbers too large for a double are rejected", "[core][scene_loader]" TIER_UNIT) {
  // nlohmann::json refuses 1e999 while parsing (it would be inf), so this is located by line and column.
  const std::string text = scene_text(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1e999, "material": "white"}])");
  REQUIRE_THROWS_AS(parse(text), InputError);
  size_t at = text.find("1e999"), line_start = text.rfind('\n', at) + 1;
  const size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  REQUIRE_THROWS_WITH(parse(text), StartsWith("test.json:" + std::to_string(line) + ":" + std::to_string(at - line_start + 1) + ": ") &&
                                       Contains("1e999"));
  // A non-finite number that does reach the reader (from a document built in code) is refused by name.
  const JsonReader reader("test.json");
  REQUIRE_THROWS_WITH(reader.number(nlohmann::json(std::numeric_limits<double>::infinity()), "/objects/0/radius"),
                      Contains("test.json: /objects/0/radius: ") && Contains("not finite"));
  REQUIRE_THROWS_WITH(reader.vec3(nlohmann::json::array({0.0, std::nan(""), 1.0}), "/camera/position"),
                      Contains("/camera/position/1: ") && Contains("not finite"));
}

TEST_CASE("scene loader: a degenerate triangle is a warning, not an error", "[core][scene_loader]" TIER_UNIT) {
  const std::string objects = "[" + kSphere + R"(,
    {"type": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]], "material": "white"}])";
  LoadedScene loaded;
  REQUIRE_NOTHROW(loaded = parse(scene_text(objects)));
  CHECK(loaded.triangle_count == 0);
  CHECK(loaded.sphere_count == 1);
  CHECK(loaded.scene->accel().primitives().size() == 1);
  bool named = false;
  for (const std::string& w : loaded.warnings) named = named || (w.find("/objects/1") != std::string::npos && w.find("degenerate") != std::string::npos);
  CHECK(named);
  // An emissive degenerate triangle would be a zero-area light: that is an error.
  const std::string emissive = "[" + kSphere + R"(,
    {"type": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]], "material": "light"}])";
  REQUIRE_THROWS_WITH(parse(scene_text(emissive)), Contains("/objects/1: emissive object has zero area"));
}

TEST_CASE("scene loader: mesh files are resolved from the scene folder", "[core][scene_loader]" TIER_UNIT) {
  test::TempDir dir;
  const std::string missing = scene_text(R"([{"type": "mesh", "file": "models/nothing.obj", "material": "white"}])");
  REQUIRE_THROWS_AS(parse(missing, dir.path().string()), InputError);
  REQUIRE_THROWS_WITH(parse(missing, dir.path().string()),
                      Contains("/objects/0/file: ") && Contains("tried") &&
                          Contains((dir.path() / "models" / "nothing.obj").string()));

  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  const std::string found = scene_text(R"([{"type": "mesh", "file": "tri.obj", "scale": 2, "translate": [0, 0, 1], "material": "white"}])");
  const std::string path = dir.write("scene.json", found);
  LoadedScene loaded = load_scene(path);
  CHECK(loaded.triangle_count == 2);
  const Bounds b = loaded.scene->accel().bounds();
  CHECK(b.lo == Vec3(0, 0, 1));
  CHECK(b.hi == Vec3(2, 2, 1));
}

TEST_CASE("load_scene: missing files and folders are input errors", "[core][scene_loader]" TIER_UNIT) {
  test::TempDir dir;
  REQUIRE_THROWS_AS(load_scene(dir.file("nope.json")), InputError);
  REQUIRE_THROWS_WITH(load_scene(dir.file("nope.json")), Contains("nope.json") && Contains("not found"));
  REQUIRE_THROWS_AS(load_scene(dir.path().string()), InputError);
  REQUIRE_THROWS_WITH(load_scene(dir.path().string()), Contains("directory"));
  // The file name, not "test.json", starts messages from load_scene.
  const std::string bad = dir.write("bad.json", "{\n  \"camera\": 1,\n}");
  REQUIRE_THROWS_WITH(load_scene(bad), StartsWith(bad + ":3:1: "));
}

TEST_CASE("load_scene: every scene in scenes/ and tests/data loads with a light", "[core][scene_loader]" TIER_UNIT) {
  std::vector<std::string> files;
  for (const char* folder : {"/scenes", "/tests/data"}) {
    for (const auto& entry : std::filesystem::directory_iterator(std::string(CAUSTICA_SOURCE_DIR) + folder)) {
      if (entry.path().extension() == ".json") files.push_back(entry.path().string());
    }
  }
  REQUIRE(files.size() >= 6);
  for (const std::string& file : files) {
    INFO(file);
    LoadedScene loaded;
    REQUIRE_NOTHROW(loaded = load_scene(file));
    CHECK(!loaded.scene->lights.empty());
    CHECK(loaded.triangle_count + loaded.sphere_count > 0);
    CHECK(loaded.warnings.empty());
  }
}

// Regressions: the column of a syntax error was that of the last character of the
// unexpected token; and "1e999" was located by a plain text search, so an earlier string
// "1e999" took the blame.
TEST_CASE("scene loader: a syntax error at a multi-character token names its first column", "[core][regression]" TIER_UNIT) {
  const std::string text = "{\n  \"camera\": {},\n  \"render\": {\"width\": 8 \"height\": 8}\n}";
  // "height" starts at column 25 of line 3; the parser reports its closing quote, column 32.
  REQUIRE_THROWS_WITH(parse(text), StartsWith("test.json:3:25: "));
}

TEST_CASE("scene loader: number overflow is located at the number", "[core][regression]" TIER_UNIT) {
  const std::string text = "{\n  \"name\": \"1e999\",\n  \"radius\": 1e999\n}";
  REQUIRE_THROWS_WITH(parse(text), StartsWith("test.json:3:13: "));
}

TEST_CASE("scene loader: an emissive material's objects emit through their area light, front side only",
          "[io][scene_loader]" TIER_UNIT) {
  // A quad in z = 0 facing -z (edge1 x edge2), lit from the camera's side.
  LoadedScene loaded = parse_scene(
      scene_text(R"([{"type": "quad", "origin": [-1, -1, 0], "edge1": [0, 1, 0], "edge2": [1, 0, 0], "material": "light"}])"),
      "emit.json", ".");
  const Scene& scene = *loaded.scene;
  REQUIRE(scene.lights.size() == 1);
  CHECK(scene.lights[0]->surface_radiance() == Color(1, 2, 3));
  SurfaceHit hit;
  REQUIRE(scene.intersect(Ray{Vec3(-0.5f, -0.5f, -3), Vec3(0, 0, 1)}, hit));
  CHECK(hit.light == 0);
  CHECK(scene.emitted(hit, hit.frame.to_local(Vec3(0, 0, -1))) == Color(1, 2, 3));
  CHECK(is_black(scene.emitted(hit, hit.frame.to_local(Vec3(0, 0, 1)))));
  // A non-emissive object's hits emit nothing.
  LoadedScene plain = parse_scene(
      scene_text(R"([{"type": "quad", "origin": [-1, -1, 0], "edge1": [0, 1, 0], "edge2": [1, 0, 0], "material": "white"}])"),
      "plain.json", ".");
  REQUIRE(plain.scene->intersect(Ray{Vec3(-0.5f, -0.5f, -3), Vec3(0, 0, 1)}, hit));
  CHECK(hit.light == -1);
  CHECK(is_black(plain.scene->emitted(hit, Vec3(0, 0, 1))));
}

TEST_CASE("scene loader: command-line overrides apply before the scene is built", "[io][scene_loader]" TIER_UNIT) {
  const std::string text = scene_text(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}])",
                                       kMaterials,
                                       R"({"width": 40, "height": 30, "spp": 2, "crop": [10, 5, 20, 10], "accel": "embree"})");
  // The scene as written: its crop window and the backend it asks for (or our BVH, warned).
  LoadedScene plain = parse_scene(text, "o.json", ".");
  CHECK(plain.scene->render.width == 20);
  CHECK(plain.scene->camera.film_width() == 40);
  CHECK(std::string(plain.scene->accel().name()) == (embree_available() ? "embree" : "bvh"));
  RenderOverrides o;
  o.width = 64;
  o.spp = 5;
  o.seed = 9;
  o.max_depth = 3;
  o.accel = AccelKind::Bvh;
  LoadedScene over = parse_scene(text, "o.json", ".", {}, o);
  const Scene& s = *over.scene;
  // A new width is a new film: the height not given is the film's, the crop window is dropped.
  CHECK(s.render.width == 64);
  CHECK(s.render.height == 30);
  CHECK(s.camera.film_width() == 64);
  CHECK(s.camera.film_height() == 30);
  CHECK(s.render.spp == 5);
  CHECK(s.render.seed == 9);
  CHECK(s.render.max_depth == 3);
  // The accelerator was built for the backend asked for.
  CHECK(s.render.accel == AccelKind::Bvh);
  CHECK(std::string(s.accel().name()) == "bvh");
}

TEST_CASE("scene loader: a seed takes every value from 0 to 2^64 - 1, none clamped", "[io][scene_loader]" TIER_UNIT) {
  const std::string objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}])";
  for (const char* seed : {"0", "9223372036854775807", "9223372036854775808", "18446744073709551615"}) {
    INFO(seed);
    LoadedScene loaded = parse_scene(scene_text(objects, kMaterials, std::string(R"({"seed": )") + seed + "}"), "s.json", ".");
    CHECK(loaded.scene->render.seed == std::stoull(seed));
  }
  // Integers past INT64_MAX elsewhere are out of range, not clamped into it.
  CHECK_THROWS_WITH(parse_scene(scene_text(objects, kMaterials, R"({"spp": 9223372036854775808})"), "s.json", "."),
                    Contains("/render/spp: value 9223372036854775808 is out of range"));
}

TEST_CASE("scene loader: sampling_weight scales how often a light is chosen", "[io][scene_loader]" TIER_UNIT) {
  // Issue 24 (Mitsuba's sampling_weight): chosen in proportion to power times weight.
  const std::string objects = "[" + kSphere + ",\n" +
                              R"({"type": "quad", "origin": [0, 2, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "light", "sampling_weight": 2}])";
  std::string text = scene_text(objects);
  text.insert(text.rfind('}'), R"(, "lights": [{"type": "point", "position": [0, 3, 0], "intensity": 1},
    {"type": "point", "position": [1, 3, 0], "intensity": 1, "sampling_weight": 3}])");
  const LoadedScene loaded = parse(text);
  const Scene& s = *loaded.scene;
  REQUIRE(s.lights.size() == 3);
  // Powers: the quad pi * 1 * mean(1, 2, 3) = 2 pi, weighted 2; each point light 4 pi, weighted 1 and 3.
  const double pi = 3.14159265358979323846;
  const double w0 = 2.0 * 2.0 * pi, w1 = 4.0 * pi, w2 = 3.0 * 4.0 * pi, sum = w0 + w1 + w2;
  CHECK(s.photon_light_pmf(0) == Approx(w0 / sum));
  CHECK(s.photon_light_pmf(1) == Approx(w1 / sum));
  CHECK(s.photon_light_pmf(2) == Approx(w2 / sum));
  // Zero, negative, and on an object that does not emit: errors.
  std::string zero = scene_text("[" + kSphere + "]");
  zero.insert(zero.rfind('}'), R"(, "lights": [{"type": "point", "position": [0, 3, 0], "intensity": 1, "sampling_weight": 0}])");
  REQUIRE_THROWS_WITH(parse(zero), Contains("test.json: /lights/0/sampling_weight: sampling_weight must be positive"));
  const std::string dark = scene_text(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white", "sampling_weight": 2}])");
  REQUIRE_THROWS_WITH(parse(dark), Contains("test.json: /objects/0/sampling_weight: sampling_weight belongs to an object whose material emits"));
}
