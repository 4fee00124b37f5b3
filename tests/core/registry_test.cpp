// The plugin registries: every registered plugin is documented, and whatever lists a family
// (error messages, the Mitsuba translator) lists exactly the registry's rows.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/bsdf/registry.h"
#include "core/lights/registry.h"
#include "core/media/registry.h"
#include "core/textures/registry.h"
#include "io/scene_loader.h"
#include "support/errors.h"
#include "support/run.h"
#include "support/temp_dir.h"

using namespace caustica;

namespace {
std::string doc(const std::string& name) { return test::read_text(std::string(CAUSTICA_SOURCE_DIR) + "/docs/" + name); }

const char* kScene = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]},
  "materials": {"m": %s}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";

std::string scene_with(const std::string& material) {
  std::string s = kScene;
  s.replace(s.find("%s"), 2, material);
  return s;
}
}  // namespace

// Every row is in scene-format.md as `"name"`, and Mitsuba's rows in mitsuba.md as `name`.
template <class Plugin>
void check_documented(const std::vector<Plugin>& table) {
  const std::string format = doc("scene-format.md"), mitsuba = doc("mitsuba.md");
  for (const Plugin& p : table) {
    INFO(p.name);
    CHECK(format.find("`\"" + std::string(p.name) + "\"`") != std::string::npos);
    if (p.mitsuba) CHECK(mitsuba.find("`" + std::string(p.name) + "`") != std::string::npos);
  }
}

TEST_CASE("registries: the docs name every registered plugin", "[core][registry]" TIER_UNIT) {
  REQUIRE(bsdf_plugins().size() >= 14);
  check_documented(bsdf_plugins());
  REQUIRE(texture_plugins().size() >= 2);
  check_documented(texture_plugins());
  REQUIRE(light_plugins().size() >= 5);
  check_documented(light_plugins());
  REQUIRE(medium_plugins().size() >= 1);
  check_documented(medium_plugins());
  REQUIRE(phase_plugins().size() >= 2);
  check_documented(phase_plugins());
  REQUIRE(volume_plugins().size() >= 2);
  check_documented(volume_plugins());
  // Shapes: every row of the table in scene-format.md (their Mitsuba names are translated).
  const std::string format = doc("scene-format.md");
  for (const PluginListing& p : scene_plugins()) {
    if (p.family != "shape") continue;
    INFO(p.name);
    CHECK(format.find("### `\"" + p.name + "\"`") != std::string::npos);
  }
}

TEST_CASE("registries: the BSDF table drives the JSON reader's errors and the Mitsuba translator", "[core][registry]" TIER_UNIT) {
  const std::string error = test::error_of([] { parse_scene(scene_with(R"({"type": "velvet"})"), "s.json", "."); });
  REQUIRE_FALSE(error.empty());
  for (const BsdfPlugin& p : bsdf_plugins()) {
    INFO(p.name);
    CHECK(error.find(std::string(p.name)) != std::string::npos);
    // Each plugin reads with its defaults alone, except those whose nested BSDF is required.
    const bool needs_bsdf = std::find(p.keys.begin(), p.keys.end(), std::string("bsdf")) != p.keys.end();
    if (!needs_bsdf) CHECK_NOTHROW(parse_scene(scene_with(R"({"type": ")" + std::string(p.name) + R"("})"), "s.json", "."));
    // A key outside the row is refused, naming the place.
    CHECK(test::error_of([&] { parse_scene(scene_with(R"({"type": ")" + std::string(p.name) + R"(", "colour": 1})"), "s.json", "."); })
              .find("/materials/m/colour: unknown key") != std::string::npos);
  }
  // Mitsuba's BSDFs are the rows it knows by name; our aliases are not Mitsuba plugins.
  const std::string sensor = R"(<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>)";
  for (const BsdfPlugin& p : bsdf_plugins()) {
    INFO(p.name);
    const std::string xml = R"(<scene version="3.0.0">)" + sensor + R"(<shape type="sphere"><bsdf type=")" + p.name +
                            R"("/></shape><emitter type="constant"/></scene>)";
    const std::string e = test::error_of([&] { parse_scene(xml, "s.xml", "."); });
    if (p.mitsuba) CHECK(e.find("unsupported") == std::string::npos);
    else CHECK(e.find("unsupported") != std::string::npos);
  }
}

TEST_CASE("registries: caustica plugins lists every row, and its fuzz dictionaries every name", "[core][registry]" TIER_PROCESS) {
  test::TempDir dir;
  const test::RunResult list = test::run_caustica("plugins", dir);
  REQUIRE(list.exit_code == 0);
  size_t rows = 0;
  for (const BsdfPlugin& p : bsdf_plugins()) rows += list.out.find("bsdf " + std::string(p.name)) != std::string::npos;
  for (const TexturePlugin& p : texture_plugins()) rows += list.out.find("texture " + std::string(p.name)) != std::string::npos;
  for (const LightPlugin& p : light_plugins()) rows += list.out.find("light " + std::string(p.name)) != std::string::npos;
  CHECK(rows == bsdf_plugins().size() + texture_plugins().size() + light_plugins().size());
  for (const char* shape : {"shape sphere:", "shape triangle:", "shape quad:", "shape mesh:", "integrator photon:"}) {
    CHECK(list.out.find(shape) != std::string::npos);
  }
  const test::RunResult json = test::run_caustica("plugins --dict json", dir);
  const test::RunResult xml = test::run_caustica("plugins --dict xml", dir);
  REQUIRE(json.exit_code == 0);
  REQUIRE(xml.exit_code == 0);
  for (const BsdfPlugin& p : bsdf_plugins()) {
    INFO(p.name);
    CHECK(json.out.find("\"\\\"" + std::string(p.name) + "\\\"\"") != std::string::npos);
    if (p.mitsuba) CHECK(xml.out.find("\"<bsdf type=\\\"" + std::string(p.name) + "\\\">\"") != std::string::npos);
  }
}
