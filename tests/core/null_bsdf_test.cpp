// Mitsuba's `null` BSDF: rays, shadow rays and photons pass through it, so a null surface
// changes no image; read from JSON and from Mitsuba XML through the BSDF registry.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/bsdf/null.h"
#include "core/bsdf/registry.h"
#include "io/scene_loader.h"
#include "support/render_util.h"

using namespace caustica;

namespace {
// A floor lit by a square lamp above it, seen from the side; `middle` is the material of a
// quad halfway between lamp and floor that covers the lamp's whole footprint (none when empty).
std::string lamp_scene(const std::string& middle) {
  const std::string quads = middle.empty() ? "" : R"(,
    {"type": "quad", "origin": [-1, 1, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "middle"},
    {"type": "quad", "origin": [-1, 1, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0], "material": "middle"})";
  return R"({
  "camera": {"position": [0, 1.2, 4], "look_at": [0, 0.3, 0], "fov": 50},
  "render": {"width": 24, "height": 24, "spp": 1},
  "materials": {"white": {"type": "diffuse", "reflectance": 0.6},
                "lamp": {"type": "diffuse", "reflectance": 0, "emission": 5},
                "middle": )" + (middle.empty() ? "{\"type\": \"null\"}" : middle) + R"(},
  "objects": [
    {"type": "quad", "origin": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "white"},
    {"type": "quad", "origin": [-0.5, 2, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "lamp"})" + quads + R"(
  ]
})";
}

double mean_of(const std::string& scene, const std::string& integrator, const std::string& settings) {
  const test::TestRender r = test::render_text(scene, integrator, settings, 16, 24, 24, 3);
  REQUIRE(r.stats.bad_samples == 0);
  const Color m = r.image.mean();
  return (double(m.x) + m.y + m.z) / 3.0;
}
}  // namespace

TEST_CASE("null: a ray passes through the surface to what lies behind it", "[core][bsdf][null]" TIER_UNIT) {
  LoadedScene loaded = parse_scene(lamp_scene(R"({"type": "null"})"), "null.json", ".");
  const Scene& scene = *loaded.scene;
  SurfaceHit hit;
  // Straight down through both sides of the null quad (y = 1) onto the floor (y = 0).
  REQUIRE(scene.intersect(Ray{Vec3(0.7f, 1.5f, 0.7f), Vec3(0, -1, 0)}, hit));
  CHECK(hit.p.y == Approx(0.0f).margin(1e-4));
  CHECK_FALSE(scene.occluded(Ray{Vec3(0.2f, 0.01f, 0.2f), Vec3(0, 1, 0), 1.9f}));
  // Wrapped in twosided or in a fully opaque mask, it is still not there.
  for (const char* wrapped : {R"({"type": "twosided", "bsdf": {"type": "null"}})",
                              R"({"type": "mask", "opacity": 1, "bsdf": {"type": "null"}})"}) {
    INFO(wrapped);
    LoadedScene w = parse_scene(lamp_scene(wrapped), "wrapped.json", ".");
    REQUIRE(w.scene->intersect(Ray{Vec3(0.7f, 1.5f, 0.7f), Vec3(0, -1, 0)}, hit));
    CHECK(hit.p.y == Approx(0.0f).margin(1e-4));
  }
  // The same quad with a diffuse material stops both.
  LoadedScene solid = parse_scene(lamp_scene(R"({"type": "diffuse"})"), "solid.json", ".");
  REQUIRE(solid.scene->intersect(Ray{Vec3(0.7f, 1.5f, 0.7f), Vec3(0, -1, 0)}, hit));
  CHECK(hit.p.y == Approx(1.0f).margin(1e-4));
  CHECK(solid.scene->occluded(Ray{Vec3(0.2f, 0.01f, 0.2f), Vec3(0, 1, 0), 1.9f}));
}

TEST_CASE("null: path and photon render the lamp scene as if the null surface were not there", "[core][bsdf][null]" TIER_UNIT) {
  const std::string without = lamp_scene("");
  const std::string with_null = lamp_scene(R"({"type": "null"})");
  const std::string with_blocker = lamp_scene(R"({"type": "diffuse", "reflectance": 0})");
  for (const auto& [integrator, settings] : {std::pair<std::string, std::string>{"path", "{}"},
                                             {"photon", R"({"photons": 20000, "progressive": false})"}}) {
    INFO(integrator);
    const double reference = mean_of(without, integrator, settings);
    REQUIRE(reference > 0.01);
    // Same seed, same samples: only the hit offsets differ, so the means agree closely.
    CHECK(mean_of(with_null, integrator, settings) == Approx(reference).epsilon(0.01));
    // A test that could fail: a blocking quad darkens the floor by far more than that.
    CHECK(mean_of(with_blocker, integrator, settings) < 0.8 * reference);
  }
}

TEST_CASE("null: the registry's row, JSON and Mitsuba XML", "[core][bsdf][null]" TIER_UNIT) {
  const BsdfPlugin* row = find_bsdf_plugin("null");
  REQUIRE(row);
  CHECK(row->mitsuba);
  CHECK_FALSE(row->can_emit);
  CHECK(row->keys.empty());
  CHECK_THROWS_WITH(parse_scene(lamp_scene(R"({"type": "null", "emission": 1})"), "null.json", "."),
                    Catch::Matchers::Contains("/materials/middle/emission: a null material cannot emit light"));
  CHECK_THROWS_WITH(parse_scene(lamp_scene(R"({"type": "null", "opacity": 1})"), "null.json", "."),
                    Catch::Matchers::Contains("/materials/middle/opacity") && Catch::Matchers::Contains("unknown key"));
  const std::string xml = R"(<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <bsdf type="null" id="invisible"/>
  <shape type="rectangle"><ref id="invisible"/></shape>
  <shape type="sphere"><float name="radius" value="0.5"/><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
</scene>)";
  LoadedScene loaded = parse_scene(xml, "null.xml", ".");
  size_t nulls = 0;
  for (const auto& m : loaded.scene->materials) nulls += dynamic_cast<const NullBsdf*>(m.get()) != nullptr;
  CHECK(nulls == 1);
  // A ray through the rectangle (z = 0) beside the sphere hits nothing.
  SurfaceHit hit;
  CHECK_FALSE(loaded.scene->intersect(Ray{Vec3(0.8f, 0.8f, 5), Vec3(0, 0, -1)}, hit));
  CHECK(loaded.scene->intersect(Ray{Vec3(0.0f, 0.0f, 5), Vec3(0, 0, -1)}, hit));
  CHECK(hit.p.z == Approx(0.5f).margin(1e-3));
}
