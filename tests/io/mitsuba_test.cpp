// Mitsuba XML scenes: the same scene written in XML and in our JSON renders bit for bit the
// same; every property type, transform, <default>/$name/-D, <include>, <path>, <ref>, the 0.6
// names, the sensor (fov_axis, mirror, crop), sampler and integrator settings, the analytic
// shapes; and each class of error names file:line:column and the element.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include <functional>
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>
#include "io/image_io.h"
#include "io/json_reader.h"
#include "io/mitsuba/spectrum.h"
#include "io/mitsuba/translate.h"
#include "io/mitsuba/xml_tree.h"
#include "io/scene_loader.h"
#include "io/volume_io.h"
#include "support/grids.h"
#include "support/errors.h"
#include "support/render_util.h"
#include "support/temp_dir.h"
#include "trace/integrator.h"
#include "trace/render.h"

using namespace caustica;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;

namespace {

constexpr double kPiD = 3.14159265358979323846;

std::string xml_scene(const std::string& body, const std::string& version = "3.0.0") {
  return "<scene version=\"" + version + "\">\n" + body + "\n</scene>\n";
}

json translate(const std::string& xml, const MitsubaOptions& options = {}) {
  return read_mitsuba(xml, "scene.xml", ".", options).doc;
}

MitsubaOptions with_defines(std::vector<std::pair<std::string, std::string>> defines) {
  MitsubaOptions o;
  o.xml.defines = std::move(defines);
  return o;
}

using test::error_of;

glm::dvec3 vec3_of(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

void check_vec(const json& j, const glm::dvec3& expected, double eps = 1e-12) {
  INFO("got " << j.dump() << ", expected (" << expected.x << ", " << expected.y << ", " << expected.z << ")");
  REQUIRE(j.is_array());
  REQUIRE(j.size() == 3);
  const glm::dvec3 v = vec3_of(j);
  for (int i = 0; i < 3; ++i) CHECK(std::abs(v[i] - expected[i]) <= eps);
}

// The 4x4 "to_world" rows of a translated object compared with `expected` rows.
void check_rows(const json& j, const std::vector<std::vector<double>>& expected, double eps = 1e-12) {
  INFO("got " << j.dump());
  REQUIRE(j.is_array());
  REQUIRE(j.size() == expected.size());
  for (size_t r = 0; r < expected.size(); ++r) {
    REQUIRE(j[r].size() == expected[r].size());
    for (size_t c = 0; c < expected[r].size(); ++c) CHECK(std::abs(j[r][c].get<double>() - expected[r][c]) <= eps);
  }
}

// A sensor and a sphere around a body, enough for parse_scene to build a scene.
std::string loadable(const std::string& body, const std::string& film = "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>") {
  return xml_scene(R"(  <sensor type="perspective">
    <float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 0, 10" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm">)" + film + R"(</film>
  </sensor>
)" + body);
}

double total_area(const Scene& scene) {
  double a = 0.0;
  for (const ObjectInfo& o : scene.objects) a += o.area;
  return a;
}

// Renders a loaded scene as the application does: the scene's integrator, size, spp and seed.
Image render_loaded(LoadedScene& loaded) {
  Scene& scene = *loaded.scene;
  auto integ = create_integrator(loaded.integrator_type, loaded.integrator_settings, scene.render);
  integ->preprocess(scene, {scene.render.seed, true});
  RenderOptions options;
  options.job.passes = scene.render.spp;
  options.job.seed = scene.render.seed;
  options.quiet = true;
  RenderStats stats;
  return render_image(scene, *integ, options, stats);
}

double max_value(const Image& img) {
  double m = 0.0;
  for (const Color& c : img.pixels) m = std::max({m, double(c.r), double(c.g), double(c.b)});
  return m;
}

}  // namespace

// ------------------------------------------------------------------------------------------
// 1. The same scene in XML and JSON

TEST_CASE("mitsuba: a scene in XML renders bit-identically to the same scene in JSON", "[mitsuba]" TIER_UNIT) {
  const std::string xml = R"(<?xml version="1.0" encoding="utf-8"?>
<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="4"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 1, 5" target="0, 1, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/><rfilter type="box"/></film>
  </sensor>
  <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.7, 0.6, 0.5"/></bsdf>
  <bsdf type="diffuse" id="checker">
    <texture type="checkerboard" name="reflectance">
      <rgb name="color0" value="0.8, 0.8, 0.8"/>
      <rgb name="color1" value="0.1, 0.2, 0.3"/>
      <transform name="to_uv"><scale value="4"/></transform>
    </texture>
  </bsdf>
  <bsdf type="roughconductor" id="metal">
    <string name="material" value="Au"/>
    <float name="alpha" value="0.2"/>
  </bsdf>
  <shape type="rectangle" id="floor">
    <transform name="to_world"><matrix value="2 0 0 0  0 0 2 0  0 -2 0 0  0 0 0 1"/></transform>
    <ref id="checker"/>
  </shape>
  <shape type="sphere" id="ball">
    <point name="center" x="-0.5" y="0.5" z="0"/>
    <float name="radius" value="0.5"/>
    <ref id="metal"/>
  </shape>
  <shape type="sphere" id="pebble">
    <point name="center" value="0.75, 0.25, 0.5"/>
    <float name="radius" value="0.25"/>
    <ref id="white"/>
  </shape>
  <shape type="rectangle" id="lamp">
    <transform name="to_world"><matrix value="0.5 0 0 0  0 0 -0.5 2.5  0 0.5 0 0  0 0 0 1"/></transform>
    <emitter type="area"><rgb name="radiance" value="4, 4, 4"/></emitter>
  </shape>
  <emitter type="point">
    <point name="position" value="1, 2, 2"/>
    <rgb name="intensity" value="3, 3, 3"/>
  </emitter>
</scene>
)";
  const std::string rect = R"("vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
      "indices": [[0, 1, 2], [0, 2, 3]], "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]])";
  const std::string json_text = R"({
  "render": {"width": 32, "height": 32, "spp": 4, "max_depth": 3},
  "camera": {"position": [0, 1, 5], "look_at": [0, 1, 4], "up": [0, 1, 0], "fov": 40, "fov_axis": "x"},
  "integrator": {"type": "path", "rr_depth": 5},
  "materials": {
    "white": {"type": "diffuse", "reflectance": [0.7, 0.6, 0.5]},
    "checker": {"type": "diffuse", "reflectance": {"type": "checkerboard", "color0": [0.8, 0.8, 0.8],
                "color1": [0.1, 0.2, 0.3], "to_uv": [[4, 0, 0], [0, 4, 0]]}},
    "metal": {"type": "roughconductor", "material": "Au", "alpha": 0.2, "distribution": "beckmann"},
    "default diffuse + emitter 1": {"type": "diffuse", "reflectance": 0.5, "emission": [4, 4, 4]}
  },
  "objects": [
    {"type": "mesh", "name": "floor", "material": "checker", )" + rect + R"(,
     "to_world": [[2, 0, 0, 0], [0, 0, 2, 0], [0, -2, 0, 0], [0, 0, 0, 1]]},
    {"type": "sphere", "name": "ball", "material": "metal", "center": [-0.5, 0.5, 0], "radius": 0.5},
    {"type": "sphere", "name": "pebble", "material": "white", "center": [0.75, 0.25, 0.5], "radius": 0.25},
    {"type": "mesh", "name": "lamp", "material": "default diffuse + emitter 1", )" + rect + R"(,
     "to_world": [[0.5, 0, 0, 0], [0, 0, -0.5, 2.5], [0, 0.5, 0, 0], [0, 0, 0, 1]]}
  ],
  "lights": [{"type": "point", "position": [1, 2, 2], "intensity": [3, 3, 3]}]
})";
  // The translation is what the JSON above spells out.
  const TranslatedScene t = read_mitsuba(xml, "scene.xml", ".", {});
  CHECK(t.warnings.empty());
  const json& d = t.doc;
  CHECK(d["render"] == json({{"width", 32}, {"height", 32}, {"spp", 4}, {"max_depth", 3}, {"filter", "box"}}));
  CHECK(d["integrator"] == json({{"type", "path"}, {"rr_depth", 5}}));
  CHECK(d["camera"] == json::parse(R"({"position": [0, 1, 5], "look_at": [0, 1, 4], "up": [0, 1, 0], "fov": 40, "fov_axis": "x"})"));
  REQUIRE(d["objects"].size() == 4);
  CHECK(d["objects"][3]["material"] == "default diffuse + emitter 1");
  CHECK(d["lights"] == json::parse(R"([{"type": "point", "position": [1, 2, 2], "intensity": [3, 3, 3]}])"));

  LoadedScene from_xml = parse_scene(xml, "scene.xml", ".");
  LoadedScene from_json = parse_scene(json_text, "scene.json", ".");
  CHECK(from_xml.triangle_count == 4);
  CHECK(from_xml.sphere_count == 2);
  CHECK(from_json.triangle_count == 4);
  CHECK(from_xml.scene->render.max_depth == 3);
  CHECK(from_xml.scene->lights.size() == 2);
  CHECK(from_xml.scene->material_names == from_json.scene->material_names);

  const test::TestRender a = test::render_text(xml, "path", R"({"rr_depth": 5})", 4, 32, 32, 3);
  const test::TestRender b = test::render_text(json_text, "path", R"({"rr_depth": 5})", 4, 32, 32, 3);
  REQUIRE(a.image.width == 32);
  REQUIRE(a.image.height == 32);
  REQUIRE(b.image.width == 32);
  REQUIRE(b.image.height == 32);
  // Not a black or flat image: the lamp, the lit floor and the spheres are seen.
  CHECK(max_value(a.image) > 1.0);
  CHECK(test::region_mean(a.image, 0, 16, 32, 32).y > 0.01);
  int differing = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const Color p = a.image.at(x, y), q = b.image.at(x, y);
      if (p.r != q.r || p.g != q.g || p.b != q.b) ++differing;
    }
  }
  CHECK(differing == 0);
  // And through the scene's own settings (integrator, spp and seed of the file).
  const Image c = render_loaded(from_xml), e = render_loaded(from_json);
  REQUIRE(c.pixels.size() == e.pixels.size());
  differing = 0;
  for (size_t i = 0; i < c.pixels.size(); ++i) differing += c.pixels[i] != e.pixels[i];
  CHECK(differing == 0);
}

// ------------------------------------------------------------------------------------------
// 2. Property types

TEST_CASE("mitsuba: every property type is read with its value", "[mitsuba]" TIER_UNIT) {
  const std::string xml = xml_scene(R"(  <bsdf type="diffuse" id="p">
    <integer name="i" value="-7"/>
    <float name="f" value="2.5e-1"/>
    <boolean name="b" value="true"/>
    <boolean name="b2" value="False"/>
    <string name="s" value="hello world"/>
    <rgb name="c3" value="0.1, 0.2 0.3"/>
    <rgb name="c1" value="0.25"/>
    <srgb name="hex" value="#ff8000"/>
    <spectrum name="sc" value="0.75"/>
    <spectrum name="sp" value="400:0.1, 500:0.2, 600:0.3"/>
    <vector name="v1" value="1, -2, 3.5"/>
    <point name="v2" x="4" y="5" z="-6"/>
    <point name="v3" y="7"/>
  </bsdf>)");
  const XmlScene tree = parse_mitsuba_xml(xml, "scene.xml", ".", {});
  REQUIRE(tree.root().children.size() == 1);
  const XmlObject& o = *tree.root().children[0].object;
  CHECK(o.tag == "bsdf");
  CHECK(o.type == "diffuse");
  CHECK(o.id == "p");
  CHECK(o.where == "scene.xml:2:4: <bsdf type=\"diffuse\" id=\"p\">");
  REQUIRE(o.props.size() == 13);
  auto prop = [&](const char* name) {
    const XmlProperty* p = o.prop(name);
    INFO(name);
    REQUIRE(p != nullptr);
    return *p;
  };
  CHECK(prop("i").kind == XmlProperty::Integer);
  CHECK(prop("i").number == -7.0);
  CHECK(prop("i").where == "scene.xml:3:6: <integer name=\"i\">");
  CHECK(prop("f").kind == XmlProperty::Float);
  CHECK(prop("f").number == 0.25);
  CHECK(prop("b").kind == XmlProperty::Boolean);
  CHECK(prop("b").boolean);
  CHECK_FALSE(prop("b2").boolean);
  CHECK(prop("s").kind == XmlProperty::String);
  CHECK(prop("s").text == "hello world");
  CHECK(prop("c3").kind == XmlProperty::Rgb);
  CHECK(prop("c3").vec == glm::dvec3(0.1, 0.2, 0.3));
  CHECK(prop("c1").vec == glm::dvec3(0.25));
  // sRGB #ff8000 linearised: 255 -> 1, 128 -> ((128/255 + 0.055) / 1.055)^2.4, 0 -> 0.
  CHECK(prop("hex").kind == XmlProperty::Rgb);
  CHECK(prop("hex").vec.x == Approx(1.0).margin(1e-7));
  CHECK(prop("hex").vec.y == Approx(0.2158605).margin(1e-6));
  CHECK(prop("hex").vec.z == 0.0);
  CHECK(prop("sc").kind == XmlProperty::Spectrum);
  CHECK(prop("sc").samples.empty());
  CHECK(prop("sc").number == 0.75);
  CHECK(prop("sp").kind == XmlProperty::Spectrum);
  CHECK(prop("sp").samples == std::vector<std::pair<double, double>>{{400, 0.1}, {500, 0.2}, {600, 0.3}});
  CHECK(prop("v1").kind == XmlProperty::Vector);
  CHECK(prop("v1").vec == glm::dvec3(1, -2, 3.5));
  CHECK(prop("v2").vec == glm::dvec3(4, 5, -6));
  CHECK(prop("v3").vec == glm::dvec3(0, 7, 0));  // missing coordinates are 0

  // The same values in the translated material.
  const json m = translate(xml)["materials"]["p"];
  CHECK(m["type"] == "diffuse");
  CHECK(m["i"] == -7);
  CHECK(m["i"].is_number_integer());
  CHECK(m["f"] == 0.25);
  CHECK(m["b"] == true);
  CHECK(m["b2"] == false);
  CHECK(m["s"] == "hello world");
  check_vec(m["c3"], {0.1, 0.2, 0.3}, 1e-7);
  check_vec(m["c1"], glm::dvec3(0.25), 0.0);
  check_vec(m["hex"], {1.0, 0.2158605, 0.0}, 1e-6);
  CHECK(m["sc"] == 0.75);
  check_vec(m["v1"], {1, -2, 3.5}, 0.0);
  check_vec(m["v2"], {4, 5, -6}, 0.0);
}

TEST_CASE("mitsuba: spectra given as wavelength:value pairs become RGB", "[mitsuba]" TIER_UNIT) {
  const std::string xml = xml_scene(R"(
  <bsdf type="diffuse" id="grey"><spectrum name="reflectance" value="360:0.5, 830:0.5"/></bsdf>
  <bsdf type="diffuse" id="many"><spectrum name="reflectance" value="360:0.5 500:0.5, 600:0.5, 830:0.5"/></bsdf>
  <emitter type="point"><spectrum name="intensity" value="360:1, 830:1"/></emitter>
  <emitter type="point"><spectrum name="intensity" value="1"/></emitter>
  <emitter type="point"><spectrum name="intensity" value="2"/></emitter>
  <emitter type="point"><rgb name="intensity" value="1, 1, 1"/></emitter>)");
  const json d = translate(xml);
  check_vec(d["materials"]["grey"]["reflectance"], glm::dvec3(0.5), 1e-3);
  check_vec(d["materials"]["many"]["reflectance"], glm::dvec3(0.5), 1e-3);
  // An emitter's flat spectrum of 1 is Mitsuba 3's (1.2048, 0.9483, 0.9089) within 2 %.
  const glm::dvec3 flat = vec3_of(d["lights"][0]["intensity"]);
  CHECK(flat.x == Approx(1.2048).epsilon(0.02));
  CHECK(flat.y == Approx(0.9483).epsilon(0.02));
  CHECK(flat.z == Approx(0.9089).epsilon(0.02));
  // A constant spectrum on an emitter is the same flat spectrum, scaled.
  check_vec(d["lights"][1]["intensity"], flat, 1e-4);
  check_vec(d["lights"][2]["intensity"], 2.0 * flat, 2e-4);
  // An RGB intensity is taken as it is.
  check_vec(d["lights"][3]["intensity"], glm::dvec3(1.0), 0.0);
  // The same through the public conversion.
  const Color c = spectrum_to_rgb({{360, 1}, {830, 1}}, SpectrumUse::Emission);
  CHECK(c.r == Approx(flat.x).epsilon(1e-6));
  CHECK(constant_spectrum_to_rgb(0.3, SpectrumUse::Reflectance) == Color(0.3f));
}

TEST_CASE("mitsuba: vectors and points as value or as x, y, z attributes are the same", "[mitsuba]" TIER_UNIT) {
  const json d = translate(xml_scene(R"(
  <emitter type="point"><point name="position" value="1.5, -2, 3"/></emitter>
  <emitter type="point"><point name="position" x="1.5" y="-2" z="3"/></emitter>
  <emitter type="directional"><vector name="direction" value="0, 0, -2"/></emitter>
  <emitter type="directional"><vector name="direction" z="-2"/></emitter>)"));
  check_vec(d["lights"][0]["position"], {1.5, -2, 3}, 0.0);
  check_vec(d["lights"][1]["position"], {1.5, -2, 3}, 0.0);
  check_vec(d["lights"][2]["direction"], {0, 0, -1}, 0.0);  // normalised
  check_vec(d["lights"][3]["direction"], {0, 0, -1}, 0.0);
  CHECK_THAT(error_of([] { translate(xml_scene(R"(<emitter type="point"><point name="position" value="1, 2" /></emitter>)")); }),
             StartsWith("scene.xml:2:24: <point name=\"position\">: value: expected 3 numbers"));
}

// ------------------------------------------------------------------------------------------
// 3. Transforms

TEST_CASE("mitsuba: transforms translate, rotate, scale, matrix and lookat", "[mitsuba]" TIER_UNIT) {
  auto light_at = [](const std::string& ops) {
    const json d = translate(xml_scene("<emitter type=\"point\"><transform name=\"to_world\">" + ops + "</transform></emitter>"));
    return d["lights"][0]["position"];
  };
  SECTION("translate by value and by x, y, z") {
    check_vec(light_at(R"(<translate value="1, 2, 3"/>)"), {1, 2, 3}, 0.0);
    check_vec(light_at(R"(<translate x="1" z="3"/>)"), {1, 0, 3}, 0.0);
  }
  SECTION("rotate (1, 0, 0) by 90 degrees about z gives (0, 1, 0)") {
    check_vec(light_at(R"(<translate x="1"/><rotate z="1" angle="90"/>)"), {0, 1, 0}, 1e-15);
    // About x, (0, 1, 0) goes to (0, 0, 1); about y, (0, 0, 1) goes to (1, 0, 0) (right-handed).
    check_vec(light_at(R"(<translate y="1"/><rotate x="1" angle="90"/>)"), {0, 0, 1}, 1e-15);
    check_vec(light_at(R"(<translate z="1"/><rotate value="0, 3, 0" angle="90"/>)"), {1, 0, 0}, 1e-15);
    // 120 degrees about the diagonal cycles the axes: x -> y.
    check_vec(light_at(R"(<translate x="1"/><rotate x="1" y="1" z="1" angle="120"/>)"), {0, 1, 0}, 1e-15);
  }
  SECTION("composition order: each operation applies after the ones before it") {
    // translate then rotate: (1, 0, 0) rotated to (0, 1, 0); rotate then translate: the origin
    // rotated stays, then moves to (1, 0, 0).
    check_vec(light_at(R"(<translate x="1"/><rotate z="1" angle="90"/>)"), {0, 1, 0}, 1e-15);
    check_vec(light_at(R"(<rotate z="1" angle="90"/><translate x="1"/>)"), {1, 0, 0}, 1e-15);
    check_vec(light_at(R"(<translate x="1"/><scale value="2"/>)"), {2, 0, 0}, 0.0);
    check_vec(light_at(R"(<scale value="2"/><translate x="1"/>)"), {1, 0, 0}, 0.0);
    check_vec(light_at(R"(<translate value="1, 1, 1"/><scale x="2" y="3" z="4"/><translate x="-1"/>)"), {1, 3, 4}, 0.0);
  }
  SECTION("scale uniform and per axis on a rectangle") {
    auto rect = [](const std::string& ops) {
      return translate(xml_scene("<shape type=\"rectangle\"><transform name=\"to_world\">" + ops + "</transform></shape>"))["objects"][0];
    };
    check_rows(rect(R"(<scale value="2"/>)")["to_world"], {{2, 0, 0, 0}, {0, 2, 0, 0}, {0, 0, 2, 0}, {0, 0, 0, 1}}, 0.0);
    check_rows(rect(R"(<scale x="2" y="3"/>)")["to_world"], {{2, 0, 0, 0}, {0, 3, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}, 0.0);
    check_rows(rect(R"(<scale value="2, 3, 4"/>)")["to_world"], {{2, 0, 0, 0}, {0, 3, 0, 0}, {0, 0, 4, 0}, {0, 0, 0, 1}}, 0.0);
    // 16 numbers, row by row.
    check_rows(rect(R"(<matrix value="1 2 3 4 5 6 7 8 9 10 11 12 0 0 0 1"/>)")["to_world"],
               {{1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}, {0, 0, 0, 1}}, 0.0);
    // A rotation about z by 90 degrees, then a translation: rows of R with the translation last.
    check_rows(rect(R"(<rotate z="1" angle="90"/><translate value="5, 6, 7"/>)")["to_world"],
               {{0, -1, 0, 5}, {1, 0, 0, 6}, {0, 0, 1, 7}, {0, 0, 0, 1}}, 1e-15);
    // The identity leaves no to_world at all.
    CHECK_FALSE(rect("<scale value=\"1\"/>").contains("to_world"));
  }
  SECTION("a sphere: the transform moves the centre and scales the radius") {
    const json s = translate(xml_scene(R"(<shape type="sphere">
      <point name="center" x="1"/><float name="radius" value="0.5"/>
      <transform name="to_world"><scale value="2"/><rotate z="1" angle="90"/><translate value="0, 0, 3"/></transform>
    </shape>)"))["objects"][0];
    CHECK(s["type"] == "sphere");
    check_vec(s["center"], {0, 2, 3}, 1e-15);
    CHECK(s["radius"].get<double>() == Approx(1.0).margin(1e-15));
  }
  SECTION("lookat: origin, viewing direction along +z, up along +y") {
    const json d = translate(xml_scene(R"(<shape type="rectangle"><transform name="to_world">
      <lookat origin="1, 2, 3" target="1, 2, -7" up="0, 1, 0"/></transform></shape>)"));
    // Columns: left = up x dir = (-1, 0, 0), up = (0, 1, 0), dir = (0, 0, -1), origin.
    check_rows(d["objects"][0]["to_world"], {{-1, 0, 0, 1}, {0, 1, 0, 2}, {0, 0, -1, 3}, {0, 0, 0, 1}}, 0.0);
    const json p = translate(xml_scene(R"(<emitter type="point"><transform name="to_world">
      <lookat origin="4, 5, 6" target="0, 0, 0"/></transform></emitter>)"));
    check_vec(p["lights"][0]["position"], {4, 5, 6}, 0.0);
    const json spot = translate(xml_scene(R"(<emitter type="spot"><transform name="to_world">
      <lookat origin="0, 3, 0" target="0, 0, 0"/></transform></emitter>)"));
    check_vec(spot["lights"][0]["position"], {0, 3, 0}, 0.0);
    check_vec(spot["lights"][0]["direction"], {0, -1, 0}, 0.0);
  }
  SECTION("errors") {
    CHECK_THAT(error_of([&] { light_at(R"(<matrix value="1 2 3"/>)"); }),
               StartsWith("scene.xml:2:51: <matrix>: a matrix needs 16 numbers"));
    CHECK_THAT(error_of([&] { light_at(R"(<rotate angle="30"/>)"); }), Contains("the rotation axis is zero"));
    CHECK_THAT(error_of([&] { light_at(R"(<shear x="1"/>)"); }), Contains("unknown transform <shear>"));
  }
}

// ------------------------------------------------------------------------------------------
// 4. <default>, $name, -D, <include>, <path>, <ref>, errors, 0.6 names

TEST_CASE("mitsuba: default values, $name substitution and -D", "[mitsuba]" TIER_UNIT) {
  const std::string xml = xml_scene(R"(  <default name="r" value="0.25"/>
  <default name="rough" value="0.4"/>
  <shape type="sphere"><float name="radius" value="$r"/></shape>
  <bsdf type="roughconductor" id="m"><float name="alpha" value="$rough"/></bsdf>)");
  const json d = translate(xml);
  CHECK(d["objects"][0]["radius"] == 0.25);
  CHECK(d["materials"]["m"]["alpha"] == 0.4);
  // -D wins over <default>.
  const json e = translate(xml, with_defines({{"r", "0.5"}}));
  CHECK(e["objects"][0]["radius"] == 0.5);
  CHECK(e["materials"]["m"]["alpha"] == 0.4);
  // A parameter inside a longer value, in an attribute other than value, and in a type.
  const json f = translate(xml_scene(R"(  <default name="x" value="2"/><default name="kind" value="sphere"/>
  <shape type="$kind"><point name="center" value="$x, 1, $x"/></shape>)"));
  CHECK(f["objects"][0]["type"] == "sphere");
  check_vec(f["objects"][0]["center"], {2, 1, 2}, 0.0);
  // An unknown parameter is an error naming it and where it is used.
  const std::string bad = xml_scene(R"(  <default name="r" value="1"/>
  <shape type="sphere"><float name="radius" value="$radius"/></shape>)");
  const std::string msg = error_of([&] { translate(bad); });
  CHECK_THAT(msg, StartsWith("scene.xml:3:25: <float name=\"radius\">: unknown parameter \"$radius\""));
  CHECK_THAT(msg, Contains("-D radius="));
  // -D defines what no <default> does.
  CHECK(translate(bad, with_defines({{"radius", "3"}}))["objects"][0]["radius"] == 3.0);
}

TEST_CASE("mitsuba: include splices the included scene in and path finds meshes", "[mitsuba]" TIER_UNIT) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.path() / "parts");
  std::filesystem::create_directories(dir.path() / "meshes");
  dir.write("parts/objects.xml", xml_scene(R"(  <bsdf type="diffuse" id="red"><rgb name="reflectance" value="1, 0, 0"/></bsdf>
  <shape type="sphere" id="inc"><float name="radius" value="$r"/><ref id="red"/></shape>)"));
  dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string main = dir.write("main.xml", loadable(R"(  <default name="r" value="0.75"/>
  <path value="meshes"/>
  <shape type="sphere" id="before"><float name="radius" value="0.5"/></shape>
  <include filename="parts/objects.xml"/>
  <shape type="obj" id="tri"><string name="filename" value="tri.obj"/><ref id="red"/></shape>)"));
  const json d = read_mitsuba(test::read_text(main), main, dir.path().string(), {}).doc;
  REQUIRE(d["objects"].size() == 3);
  CHECK(d["objects"][0]["name"] == "before");
  CHECK(d["objects"][1]["name"] == "inc");
  CHECK(d["objects"][1]["radius"] == 0.75);  // the including file's <default> reaches the included one
  CHECK(d["objects"][1]["material"] == "red");
  CHECK(d["objects"][2]["material"] == "red");  // an id of the included file is known after it
  const std::string file = d["objects"][2]["file"];
  CHECK(std::filesystem::equivalent(file, dir.path() / "meshes" / "tri.obj"));
  LoadedScene loaded = load_scene(main);
  CHECK(loaded.sphere_count == 2);
  CHECK(loaded.triangle_count == 1);
  CHECK(total_area(*loaded.scene) == Approx(kPiD * (4 * 0.25 + 4 * 0.5625) + 0.5).epsilon(1e-5));
  // Without the <path>, the mesh is not found and the message says where it looked.
  const std::string no_path = dir.write("no_path.xml", loadable(R"(<shape type="obj"><string name="filename" value="tri.obj"/></shape>)"));
  CHECK_THAT(error_of([&] { load_scene(no_path); }), Contains("<string name=\"filename\">: file not found: tried"));
  // A missing include names the <include>.
  const std::string missing = dir.write("missing.xml", xml_scene(R"(<include filename="nowhere.xml"/>)"));
  CHECK_THAT(error_of([&] { load_scene(missing); }), StartsWith(missing + ":2:2: <include>: included file not found: nowhere.xml"));
}

TEST_CASE("mitsuba: ref by id, named ref, unknown and duplicate ids", "[mitsuba]" TIER_UNIT) {
  const json d = translate(xml_scene(R"(  <texture type="checkerboard" id="tex"><rgb name="color0" value="1, 0, 0"/></texture>
  <bsdf type="diffuse" id="red"><ref name="reflectance" id="tex"/></bsdf>
  <shape type="sphere"><ref id="red"/></shape>
  <shape type="sphere"><ref name="bsdf" id="red"/></shape>)"));
  REQUIRE(d["objects"].size() == 2);
  CHECK(d["objects"][0]["material"] == "red");
  CHECK(d["objects"][1]["material"] == "red");
  CHECK(d["materials"].size() == 1);
  const json& refl = d["materials"]["red"]["reflectance"];
  CHECK(refl["type"] == "checkerboard");
  check_vec(refl["color0"], {1, 0, 0}, 0.0);

  CHECK(error_of([] { translate(xml_scene(R"(  <bsdf type="diffuse" id="a"/>
  <shape type="sphere"><ref id="b"/></shape>)")); }) ==
        "scene.xml:3:25: <ref id=\"b\">: reference to an unknown id \"b\" (known: a)");
  CHECK_THAT(error_of([] { translate(xml_scene(R"(  <bsdf type="diffuse" id="a"/>
  <bsdf type="conductor" id="a"/>)")); }),
             StartsWith("scene.xml:3:4: <bsdf type=\"conductor\" id=\"a\">: the id \"a\" is already taken (by scene.xml:2:4: "));
}

TEST_CASE("mitsuba: malformed XML, a wrong root, unknown properties and unsupported plugins", "[mitsuba]" TIER_UNIT) {
  SECTION("malformed XML names line and column") {
    const std::string msg = error_of([] { translate("<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n    <float name=\"radius\" value=\"1\">\n  </shape>\n</scene>\n"); });
    CHECK_THAT(msg, StartsWith("scene.xml:4:5: malformed XML: "));
    CHECK_THAT(error_of([] { translate("<scene version=\"3.0.0\">\n  <shape type=\"sphere\" id=\"a></shape>\n</scene>"); }),
               StartsWith("scene.xml:") && Contains("malformed XML"));
  }
  SECTION("the root must be <scene> with a version") {
    CHECK(error_of([] { translate("<?xml version=\"1.0\"?>\n<shapes version=\"3.0.0\"/>\n"); }) ==
          "scene.xml:2:2: <shapes>: the root element is <shapes>; a Mitsuba scene's is <scene>");
    CHECK_THAT(error_of([] { translate("<scene>\n</scene>"); }), StartsWith("scene.xml:1:2: <scene>: the <scene> has no version"));
  }
  SECTION("an unknown property names itself, its line and the plugin") {
    CHECK(error_of([] { translate(xml_scene(R"(  <shape type="sphere">
    <float name="radius" value="1"/>
    <float name="raduis" value="2"/>
  </shape>)")); }) == "scene.xml:4:6: <float name=\"raduis\">: unknown property \"raduis\" of <shape type=\"sphere\">");
    CHECK_THAT(error_of([] { translate(xml_scene(R"(  <emitter type="point"><float name="power" value="2"/></emitter>)")); }),
               StartsWith("scene.xml:2:26: <float name=\"power\">: unknown property \"power\" of <emitter type=\"point\">"));
    CHECK_THAT(error_of([] { translate(xml_scene(R"(  <shape type="sphere"><float name="radius" value="1"/><float name="radius" value="2"/></shape>)")); }),
               Contains("the property \"radius\" is given twice"));
  }
  SECTION("an unsupported plugin is an error, or with ignore_unsupported a warning") {
    const std::string xml = xml_scene(R"(  <shape type="sphere"/>
  <shape type="heightfield"><float name="scale" value="2"/></shape>
  <emitter type="sunsky"/>)");
    const std::string msg = error_of([&] { translate(xml); });
    CHECK_THAT(msg, StartsWith("scene.xml:3:4: <shape type=\"heightfield\">: unsupported shape plugin \"heightfield\" (supported: "));
    CHECK_THAT(msg, Contains("--ignore-unsupported"));
    MitsubaOptions lenient;
    lenient.ignore_unsupported = true;
    const TranslatedScene t = read_mitsuba(xml, "scene.xml", ".", lenient);
    CHECK(t.doc["objects"].size() == 1);  // the heightfield is skipped
    CHECK(t.doc["lights"].empty());       // and the sunsky
    REQUIRE(t.warnings.size() >= 2);
    CHECK_THAT(t.warnings[0], StartsWith("scene.xml:3:4: <shape type=\"heightfield\">: unsupported shape plugin \"heightfield\""));
    CHECK_THAT(t.warnings[0], Contains("skipped"));
    CHECK_THAT(t.warnings[1], StartsWith("scene.xml:4:4: <emitter type=\"sunsky\">: unsupported emitter plugin \"sunsky\""));
  }
}

TEST_CASE("mitsuba: a 0.6 scene's camelCase names are upgraded", "[mitsuba]" TIER_UNIT) {
  const std::string xml = xml_scene(R"(  <integrator type="path"><integer name="maxDepth" value="3"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="50"/>
    <string name="fovAxis" value="y"/>
    <transform name="toWorld"><lookAt origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sampleCount" value="8"/></sampler>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="8"/></film>
  </sensor>
  <bsdf type="dielectric" id="glass"><float name="intIOR" value="1.33"/><float name="extIOR" value="1.0"/></bsdf>
  <bsdf type="diffuse" id="matte"><rgb name="diffuseReflectance" value="0.25, 0.5, 0.75"/></bsdf>
  <shape type="sphere"><transform name="toWorld"><translate x="1"/></transform><ref id="glass"/></shape>
  <shape type="sphere"><boolean name="flipNormals" value="true"/><ref id="matte"/></shape>)", "0.6.0");
  const json d = translate(xml);
  CHECK(d["render"]["max_depth"] == 2);
  CHECK(d["render"]["spp"] == 8);
  CHECK(d["render"]["width"] == 16);
  CHECK(d["render"]["height"] == 8);
  CHECK(d["camera"]["fov_axis"] == "y");
  CHECK(d["camera"]["fov"] == 50.0);
  check_vec(d["camera"]["position"], {0, 0, 5}, 0.0);
  check_vec(d["camera"]["look_at"], {0, 0, 4}, 0.0);
  CHECK(d["materials"]["glass"]["int_ior"] == 1.33);
  CHECK(d["materials"]["glass"]["ext_ior"] == 1.0);
  check_vec(d["materials"]["matte"]["reflectance"], {0.25, 0.5, 0.75}, 0.0);
  check_vec(d["objects"][0]["center"], {1, 0, 0}, 0.0);
  CHECK(d["objects"][1]["flip_normal"] == true);
  // The translated scene loads: the names are ones our readers know.
  LoadedScene loaded = parse_scene(xml, "scene.xml", ".");
  CHECK(loaded.scene->render.spp == 8);
  CHECK(loaded.scene->render.max_depth == 2);
  CHECK(loaded.scene->camera.vfov_degrees() == Approx(50.0f).epsilon(1e-5));
  // In a 3.0 scene the same camelCase name is an unknown property.
  CHECK_THAT(error_of([] { translate(xml_scene(R"(<shape type="sphere"><transform name="toWorld"><scale value="2"/></transform></shape>)")); }),
             Contains("unknown property \"toWorld\""));
}

// ------------------------------------------------------------------------------------------
// 5. Sensor, film, sampler, integrator

TEST_CASE("mitsuba: fov_axis decides what the field of view spans", "[mitsuba]" TIER_UNIT) {
  const double t = std::tan(30.0 * kPiD / 180.0);
  auto vfov_of = [](double tan_half) { return 2.0 * std::atan(tan_half) * 180.0 / kPiD; };
  struct Case {
    const char* axis;
    int w, h;
    double vfov;
  };
  const Case cases[] = {
      {"x", 40, 20, vfov_of(t * 0.5)},
      {"y", 40, 20, 60.0},
      {"smaller", 40, 20, 60.0},
      {"larger", 40, 20, vfov_of(t * 0.5)},
      {"diagonal", 40, 20, vfov_of(t * 20.0 / std::sqrt(40.0 * 40.0 + 20.0 * 20.0))},
      {"x", 20, 40, vfov_of(t * 2.0)},
      {"smaller", 20, 40, vfov_of(t * 2.0)},
      {"larger", 20, 40, 60.0},
      {"diagonal", 20, 40, vfov_of(t * 40.0 / std::sqrt(40.0 * 40.0 + 20.0 * 20.0))},
  };
  for (const Case& c : cases) {
    INFO(c.axis << " " << c.w << "x" << c.h);
    const std::string xml = xml_scene(std::string(R"(  <sensor type="perspective">
    <float name="fov" value="60"/><string name="fov_axis" value=")") + c.axis + R"("/>
    <film type="hdrfilm"><integer name="width" value=")" + std::to_string(c.w) + R"("/><integer name="height" value=")" +
                                      std::to_string(c.h) + R"("/></film>
  </sensor>
  <shape type="sphere"><point name="center" z="5"/></shape>)");
    LoadedScene loaded = parse_scene(xml, "scene.xml", ".");
    CHECK(loaded.scene->camera.width() == c.w);
    CHECK(loaded.scene->camera.height() == c.h);
    CHECK(loaded.scene->camera.vfov_degrees() == Approx(c.vfov).epsilon(1e-5));
  }
  // The default axis is x; without a sensor, Mitsuba's default camera.
  const TranslatedScene none = read_mitsuba(xml_scene("<shape type=\"sphere\"/>"), "scene.xml", ".", {});
  CHECK(none.doc["camera"]["fov_axis"] == "x");
  CHECK(none.doc["camera"]["fov"] == 45);
  CHECK(none.doc["render"]["width"] == 768);
  REQUIRE(none.warnings.size() == 1);
  CHECK_THAT(none.warnings[0], Contains("no <sensor>"));
}

TEST_CASE("mitsuba: a to_world with scale x -1 mirrors the image", "[mitsuba]" TIER_UNIT) {
  auto scene_with = [](const std::string& mirror) {
    return xml_scene(R"(  <integrator type="path"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world">)" + mirror + R"(<lookat origin="0, 0.5, 6" target="0, 0.5, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="24"/><rfilter type="box"/></film>
  </sensor>
  <bsdf type="diffuse" id="a"><rgb name="reflectance" value="0.8, 0.3, 0.2"/></bsdf>
  <shape type="sphere"><point name="center" x="-1" y="0.6" z="0"/><float name="radius" value="0.8"/><ref id="a"/></shape>
  <shape type="rectangle"><transform name="to_world"><matrix value="4 0 0 0  0 0 4 0  0 -4 0 0  0 0 0 1"/></transform></shape>
  <emitter type="point"><point name="position" value="2, 4, 3"/><rgb name="intensity" value="20, 20, 20"/></emitter>)");
  };
  const std::string plain = scene_with(""), mirrored = scene_with("<scale x=\"-1\"/>");
  CHECK_FALSE(translate(plain)["camera"].contains("mirror"));
  CHECK(translate(mirrored)["camera"]["mirror"] == true);
  check_vec(translate(mirrored)["camera"]["position"], {0, 0.5, 6}, 0.0);
  check_vec(translate(mirrored)["camera"]["look_at"], {0, 0.5, 5}, 0.0);

  LoadedScene a = parse_scene(plain, "scene.xml", "."), b = parse_scene(mirrored, "scene.xml", ".");
  const int w = 32, h = 24;
  // The ray through a pixel centre of one is the ray through the mirrored pixel of the other.
  for (int y = 0; y < h; y += 5) {
    for (int x = 0; x < w; x += 3) {
      const Ray ra = a.scene->camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f);
      const Ray rb = b.scene->camera.generate_ray(float(w - 1 - x) + 0.5f, float(y) + 0.5f);
      CHECK(glm::length(ra.dir - rb.dir) < 1e-6f);
      CHECK(ra.origin == rb.origin);
    }
  }
  const Image ia = render_loaded(a), ib = render_loaded(b);
  // Pixel (x, y) of one is pixel (w-1-x, y) of the other, up to where in the pixel the samples fall.
  double diff = 0.0, total = 0.0;
  int far = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 p(ia.at(x, y)), q(ib.at(w - 1 - x, y));
      diff += std::abs(p.x - q.x) + std::abs(p.y - q.y) + std::abs(p.z - q.z);
      total += p.x + p.y + p.z;
      if (std::abs(p.x - q.x) > 0.1 * std::max(1e-2, p.x)) ++far;
    }
  }
  CHECK(diff / total < 0.02);
  CHECK(far <= w * h / 20);  // only along silhouettes
  // The plain image is not symmetric (the sphere is on the left): pixel (x, y) of the two images
  // differ, so the comparison above means something.
  double self = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 p(ia.at(x, y)), q(ib.at(x, y));
      self += std::abs(p.x - q.x) + std::abs(p.y - q.y) + std::abs(p.z - q.z);
    }
  }
  CHECK(self / total > 0.2);
}

TEST_CASE("mitsuba: film crop, sampler sample_count and integrator max_depth", "[mitsuba]" TIER_UNIT) {
  auto scene_with = [](const std::string& film, const std::string& integrator = "<integer name=\"max_depth\" value=\"3\"/>") {
    return xml_scene(R"(  <integrator type="path">)" + integrator + R"(</integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0.5, 6" target="0, 0.5, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="3"/><integer name="seed" value="11"/></sampler>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="24"/>)" + film + R"(</film>
  </sensor>
  <bsdf type="diffuse" id="a"><rgb name="reflectance" value="0.8, 0.3, 0.2"/></bsdf>
  <shape type="sphere"><point name="center" x="-1" y="0.6" z="0"/><float name="radius" value="0.8"/><ref id="a"/></shape>
  <shape type="rectangle"><transform name="to_world"><matrix value="4 0 0 0  0 0 4 0  0 -4 0 0  0 0 0 1"/></transform></shape>
  <shape type="rectangle"><transform name="to_world"><matrix value="0.5 0 0 1  0 0 -0.5 3  0 0.5 0 1  0 0 0 1"/></transform>
    <emitter type="area"><rgb name="radiance" value="10, 10, 10"/></emitter></shape>)");
  };
  SECTION("sample_count and seed") {
    const json d = translate(scene_with(""));
    CHECK(d["render"]["spp"] == 3);
    CHECK(d["render"]["seed"] == 11);
    CHECK(d["render"]["max_depth"] == 2);
    LoadedScene loaded = parse_scene(scene_with(""), "scene.xml", ".");
    CHECK(loaded.scene->render.spp == 3);
    CHECK(loaded.scene->render.seed == 11);
    CHECK(loaded.integrator_type == "path");
  }
  SECTION("max_depth counts segments: 2 is our 1, 1 our 0, -1 is unlimited (1024), no value is unlimited") {
    auto depth = [&](const std::string& integ) { return parse_scene(scene_with("", integ), "scene.xml", ".").scene->render.max_depth; };
    CHECK(depth("<integer name=\"max_depth\" value=\"2\"/>") == 1);
    CHECK(depth("<integer name=\"max_depth\" value=\"5\"/>") == 4);
    CHECK(depth("<integer name=\"max_depth\" value=\"-1\"/>") == 1024);
    CHECK(depth("") == 1024);
    CHECK(depth("<integer name=\"max_depth\" value=\"1\"/>") == 0);  // emitters only
    CHECK_THAT(error_of([&] { depth("<integer name=\"max_depth\" value=\"0\"/>"); }),
               Contains("<integer name=\"max_depth\">: max_depth 0 is not supported"));
  }
  SECTION("a crop window renders the same pixels as the full film") {
    const std::string crop = R"(<integer name="crop_offset_x" value="8"/><integer name="crop_offset_y" value="4"/>
      <integer name="crop_width" value="16"/><integer name="crop_height" value="12"/>)";
    const json d = translate(scene_with(crop));
    CHECK(d["render"]["crop"] == json::array({8, 4, 16, 12}));
    LoadedScene full = parse_scene(scene_with(""), "scene.xml", "."), part = parse_scene(scene_with(crop), "scene.xml", ".");
    CHECK(part.scene->camera.width() == 16);
    CHECK(part.scene->camera.height() == 12);
    CHECK(part.scene->render.width == 16);
    CHECK(part.scene->render.height == 12);
    // Camera rays agree exactly at pixel centres.
    for (int y = 0; y < 12; ++y) {
      for (int x = 0; x < 16; ++x) {
        const Ray rf = full.scene->camera.generate_ray(float(x + 8) + 0.5f, float(y + 4) + 0.5f);
        const Ray rp = part.scene->camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f);
        CHECK(rf.dir == rp.dir);
      }
    }
    const Image a = render_loaded(full), b = render_loaded(part);
    REQUIRE(b.width == 16);
    REQUIRE(b.height == 12);
    CHECK(max_value(a) > 0.1);
    int differing = 0;
    double diff = 0.0;
    for (int y = 0; y < 12; ++y) {
      for (int x = 0; x < 16; ++x) {
        const Color p = a.at(x + 8, y + 4), q = b.at(x, y);
        differing += p != q;
        diff += std::abs(double(p.r) - double(q.r));
      }
    }
    INFO("mean absolute red difference " << diff / (16 * 12));
    CHECK(differing == 0);
  }
  SECTION("a crop window outside the film is an error") {
    const std::string crop = R"(<integer name="crop_offset_x" value="20"/><integer name="crop_width" value="16"/>)";
    CHECK_THAT(error_of([&] { parse_scene(scene_with(crop), "scene.xml", "."); }),
               Contains("<integer name=\"crop_width\">: the crop window reaches outside the 32x24 film"));
  }
}

// ------------------------------------------------------------------------------------------
// 6. Shapes

TEST_CASE("mitsuba: analytic shapes have their areas", "[mitsuba]" TIER_UNIT) {
  auto area_of = [](const std::string& shape) {
    LoadedScene loaded = parse_scene(loadable(shape), "scene.xml", ".");
    return total_area(*loaded.scene);
  };
  CHECK(area_of("<shape type=\"rectangle\"/>") == Approx(4.0).epsilon(1e-6));
  CHECK(area_of("<shape type=\"cube\"/>") == Approx(24.0).epsilon(1e-6));
  CHECK(area_of("<shape type=\"disk\"/>") == Approx(kPiD).epsilon(1e-3));
  CHECK(area_of(R"(<shape type="cylinder"><float name="radius" value="2"/><point name="p1" value="0, 0, 3"/></shape>)") ==
        Approx(2.0 * kPiD * 2.0 * 3.0).epsilon(1e-3));
  // A cylinder along another axis, off the origin.
  CHECK(area_of(R"(<shape type="cylinder"><point name="p0" value="1, 1, 1"/><point name="p1" value="4, 1, 1"/>
                   <float name="radius" value="0.5"/></shape>)") == Approx(2.0 * kPiD * 0.5 * 3.0).epsilon(1e-3));
  CHECK(area_of(R"(<shape type="rectangle"><transform name="to_world"><scale x="3" y="0.5"/></transform></shape>)") ==
        Approx(6.0).epsilon(1e-6));
  CHECK(area_of(R"(<shape type="cube"><transform name="to_world"><scale value="0.5"/><rotate x="1" y="2" angle="33"/></transform></shape>)") ==
        Approx(6.0).epsilon(1e-5));
  CHECK(area_of(R"(<shape type="sphere"><transform name="to_world"><scale value="2"/></transform></shape>)") ==
        Approx(4.0 * kPiD * 4.0).epsilon(1e-5));

  const json s = translate(xml_scene(R"(<shape type="sphere"><float name="radius" value="1.5"/>
    <transform name="to_world"><scale value="2"/><translate y="1"/></transform></shape>)"))["objects"][0];
  CHECK(s["radius"] == 3.0);
  check_vec(s["center"], {0, 1, 0}, 0.0);
  LoadedScene sphere = parse_scene(loadable(R"(<shape type="sphere"><float name="radius" value="1.5"/>
    <transform name="to_world"><scale value="2"/></transform></shape>)"), "scene.xml", ".");
  REQUIRE(sphere.scene->objects.size() == 1);
  CHECK(sphere.scene->objects[0].radius == 3.0f);

  CHECK_THAT(error_of([] { translate(xml_scene(R"(  <shape type="sphere">
    <transform name="to_world"><scale x="1" y="2" z="1"/></transform>
  </shape>)")); }),
             StartsWith("scene.xml:3:6: <transform name=\"to_world\">: a sphere's to_world must be a uniform scale, rotation and translation"));
  CHECK_THAT(error_of([] { translate(xml_scene(R"(<shape type="cylinder"><point name="p1" value="0, 0, 0"/></shape>)")); }),
             Contains("the cylinder has no extent"));
}

TEST_CASE("mitsuba: reference cycles, self-including files and exponential sharing are refused", "[mitsuba]" TIER_UNIT) {
  const std::string cycle = xml_scene(
      "<bsdf type=\"twosided\" id=\"a\">\n  <bsdf type=\"twosided\" id=\"b\">\n    <ref id=\"a\"/>\n  </bsdf>\n</bsdf>");
  CHECK(error_of([&] { translate(cycle); }) == "scene.xml:4:6: <ref id=\"a\">: this reference closes a cycle (an object inside itself)");
  test::TempDir dir;
  dir.write("self.xml", xml_scene("<include filename=\"self.xml\"/>"));
  CHECK_THAT(error_of([&] { load_scene(dir.file("self.xml")); }), Contains("makes a cycle") && Contains("includes itself"));
  // Issue 23: with an id before the <include>, the main file read twice said "the id is already taken".
  dir.write("with_id.xml", xml_scene("<bsdf type=\"diffuse\" id=\"w\"/>\n<include filename=\"with_id.xml\"/>"));
  CHECK_THAT(error_of([&] { load_scene(dir.file("with_id.xml")); }),
             StartsWith(dir.file("with_id.xml") + ":3:2: <include>: including ") && Contains("with_id.xml here makes a cycle"));
  dir.write("a.xml", xml_scene("<include filename=\"b.xml\"/>"));
  dir.write("b.xml", xml_scene("<bsdf type=\"diffuse\" id=\"w\"/>\n<include filename=\"a.xml\"/>"));
  CHECK_THAT(error_of([&] { load_scene(dir.file("a.xml")); }), Contains("b.xml:3:2: <include>: including ") && Contains("a.xml here makes a cycle"));
  // Each level holds the one before twice: 2^20 BSDFs if expanded.
  std::string body = "<bsdf type=\"diffuse\" id=\"l0\"/>\n";
  for (int i = 1; i <= 20; ++i) {
    body += "<bsdf type=\"twosided\" id=\"l" + std::to_string(i) + "\"><ref id=\"l" + std::to_string(i - 1) +
            "\"/><ref id=\"l" + std::to_string(i - 1) + "\"/></bsdf>\n";
  }
  CHECK_THAT(error_of([&] { translate(xml_scene(body)); }), Contains("expands to more than 100000"));
}

TEST_CASE("mitsuba: 0.6 uoffset and uscale give uv * scale + offset", "[mitsuba]" TIER_UNIT) {
  const json doc = translate(xml_scene(R"(<bsdf type="diffuse" id="m"><texture type="checkerboard" name="reflectance">
    <float name="uscale" value="2"/><float name="uoffset" value="0.5"/><float name="vscale" value="3"/>
  </texture></bsdf>)", "0.6.0"));
  const json& to_uv = doc["materials"]["m"]["reflectance"]["to_uv"];
  CHECK(to_uv == json::array({json::array({2.0, 0.0, 0.5}), json::array({0.0, 3.0, 0.0})}));
}

TEST_CASE("mitsuba: a mirroring to_world keeps a rectangle's normal, and mesh files get smooth normals", "[mitsuba]" TIER_UNIT) {
  const json doc = translate(xml_scene(R"(
    <shape type="rectangle"><transform name="to_world"><scale x="-1"/></transform></shape>
    <shape type="rectangle"><transform name="to_world"><scale z="-1"/></transform></shape>
    <shape type="rectangle"/>)"));
  // scale x = -1 reverses the winding (so flip it back: the normal stays +z, as the inverse
  // transpose leaves it); scale z = -1 keeps the winding (+z) where Mitsuba's normal is -z.
  CHECK(doc["objects"][0]["flip_normal"] == true);
  CHECK(doc["objects"][1]["flip_normal"] == true);
  CHECK_FALSE(doc["objects"][2].contains("flip_normal"));
  test::TempDir dir;
  dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string shapes = xml_scene(R"(<shape type="obj"><string name="filename" value="m.obj"/></shape>
    <shape type="obj"><string name="filename" value="m.obj"/><boolean name="face_normals" value="true"/></shape>)");
  const json files = read_mitsuba(shapes, "scene.xml", dir.path().string(), {}).doc;
  CHECK(files["objects"][0]["smooth_normals"] == true);
  CHECK_FALSE(files["objects"][1].contains("smooth_normals"));
}

TEST_CASE("mitsuba: 0.6 sppm, ppm and photonmapper become sppm, progressive photon and photon", "[mitsuba]" TIER_UNIT) {
  const std::string sensor = R"(
  <sensor type="perspective"><float name="fov" value="40"/>
    <sampler type="independent"><integer name="sampleCount" value="8"/></sampler>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="8"/></film>
  </sensor>
  <shape type="sphere"><bsdf type="diffuse"/></shape>)";
  // The sensor comes after the integrator: maxPasses still decides the samples per pixel.
  const json sppm = translate(xml_scene(R"(  <integrator type="sppm"><integer name="maxDepth" value="5"/>
    <integer name="photonCount" value="12345"/><float name="initialRadius" value="0.25"/>
    <float name="alpha" value="0.7"/><integer name="maxPasses" value="32"/></integrator>)" + sensor, "0.6.0"));
  CHECK(sppm["integrator"]["type"] == "sppm");
  CHECK(sppm["integrator"]["photons"] == 12345);
  CHECK(sppm["integrator"]["radius"].get<double>() == Approx(0.25));
  CHECK(sppm["integrator"]["alpha"].get<double>() == Approx(0.7));
  CHECK(sppm["render"]["spp"] == 32);
  CHECK(sppm["render"]["max_depth"] == 4);
  // Mitsuba's initialRadius 0 means "choose one", as a missing radius does here.
  const json automatic = translate(xml_scene(R"(  <integrator type="sppm"><float name="initialRadius" value="0"/></integrator>)" + sensor, "0.6.0"));
  CHECK_FALSE(automatic["integrator"].contains("radius"));
  CHECK(automatic["render"]["spp"] == 8);
  const json ppm = translate(xml_scene(R"(  <integrator type="ppm"><integer name="photonCount" value="5000"/></integrator>)" + sensor, "0.6.0"));
  CHECK(ppm["integrator"] == json({{"type", "photon"}, {"progressive", true}, {"photons", 5000}}));
  const json pm = translate(xml_scene(R"(  <integrator type="photonmapper"><integer name="globalPhotons" value="7000"/></integrator>)" + sensor, "0.6.0"));
  CHECK(pm["integrator"] == json({{"type", "photon"}, {"progressive", false}, {"photons", 7000}}));
  // The translated scenes load: the integrators accept every key the translation writes.
  for (const char* body : {R"(<integrator type="sppm"><integer name="photonCount" value="100"/><float name="initialRadius" value="0.25"/><float name="alpha" value="0.7"/></integrator>)",
                                  R"(<integrator type="ppm"><integer name="photonCount" value="100"/><float name="alpha" value="0.5"/></integrator>)"}) {
    LoadedScene loaded = parse_scene(xml_scene(std::string(body) + sensor, "0.6.0"), "scene.xml", ".");
    CHECK_NOTHROW(create_integrator(loaded.integrator_type, loaded.integrator_settings, loaded.scene->render));
  }
}

TEST_CASE("mitsuba: <default> values that double each other stop at 1 MiB, and long values are not echoed whole", "[mitsuba]" TIER_UNIT) {
  // Issue 23: 29 doublings of a 2 KB file took 5.9 GB and 60 s before this bound.
  std::string defaults = R"(  <default name="a0" value="xy"/>)";
  for (int i = 1; i <= 29; ++i) {
    defaults += "\n  <default name=\"a" + std::to_string(i) + "\" value=\"$a" + std::to_string(i - 1) + "$a" +
                std::to_string(i - 1) + "\"/>";
  }
  const std::string msg = error_of([&] { translate(xml_scene(defaults)); });
  // a19 is 2^20 characters; a20 would be twice that.
  CHECK_THAT(msg, StartsWith("scene.xml:22:4: <default name=\"a20\">: \"$a19\" expands this value past 1 MiB"));
  CHECK(msg.size() < 2 * InputError::kMaxLine);
  // Many uses of a value just under the bound: stopped at 64 MiB in all.
  std::string uses = R"(  <default name="b0" value="xy"/>)";
  for (int i = 1; i <= 19; ++i) {
    uses += "\n  <default name=\"b" + std::to_string(i) + "\" value=\"$b" + std::to_string(i - 1) + "$b" + std::to_string(i - 1) + "\"/>";
  }
  for (int i = 0; i < 100; ++i) uses += "\n  <default name=\"c" + std::to_string(i) + "\" value=\"$b19\"/>";
  CHECK_THAT(error_of([&] { translate(xml_scene(uses)); }), Contains("has produced more than 64 MiB of text in this scene"));
  // An error quoting a megabyte-long name keeps its start and end and says what it left out.
  const std::string name(1 << 20, 'n');
  const std::string echo = error_of([&] { translate(xml_scene("  <shape type=\"" + name + "\"/>")); });
  CHECK(echo.size() < 2 * InputError::kMaxLine);
  CHECK_THAT(echo, StartsWith("scene.xml:2:4: <shape type=\"nnnn") && Contains(" characters left out ...] "));
}

TEST_CASE("mitsuba: an area emitter declared with an id and referred to from shapes", "[mitsuba]" TIER_UNIT) {
  // Issue 24: <emitter type="area" id="e"/> at the top level was an error.
  const std::string xml = xml_scene(R"(  <emitter type="area" id="lamp"><rgb name="radiance" value="4, 3, 2"/></emitter>
  <shape type="sphere"><ref id="lamp"/></shape>
  <shape type="sphere"><point name="center" value="3, 0, 0"/><ref id="lamp"/></shape>
  <shape type="sphere"><point name="center" value="6, 0, 0"/></shape>)");
  const json d = translate(xml);
  REQUIRE(d["objects"].size() == 3);
  for (int i = 0; i < 2; ++i) {
    const json& m = d["materials"][d["objects"][i]["material"].get<std::string>()];
    check_vec(m["emission"], {4, 3, 2}, 1e-6);
  }
  CHECK_FALSE(d["materials"][d["objects"][2]["material"].get<std::string>()].contains("emission"));
  // Without an id nothing could refer to it: still an error.
  CHECK_THAT(error_of([] { translate(xml_scene(R"(  <emitter type="area"/>)")); }),
             Contains("an area emitter belongs inside a <shape> (or, with an id, is referred to from one)"));
}

TEST_CASE("mitsuba: with ignore_unsupported, unsupported media (the sensor's too) and subsurface are skipped", "[mitsuba]" TIER_UNIT) {
  // Issue 24: a medium inside the sensor, and <subsurface> inside a shape, were errors even then.
  // (Homogeneous and heterogeneous media are read since issue 26: a plugin we do not know stands in.)
  const std::string xml = xml_scene(R"(  <sensor type="perspective"><medium type="rgbfog"/></sensor>
  <shape type="sphere"><medium type="rgbfog" name="interior"/><subsurface type="dipole"/></shape>)");
  CHECK_THAT(error_of([&] { translate(xml); }),
             Contains("unsupported medium plugin \"rgbfog\" (supported: heterogeneous, homogeneous)"));
  MitsubaOptions lenient;
  lenient.ignore_unsupported = true;
  const TranslatedScene t = read_mitsuba(xml, "scene.xml", ".", lenient);
  CHECK(t.doc["objects"].size() == 1);
  CHECK_FALSE(t.doc.contains("media"));
  CHECK_FALSE(t.doc["objects"][0].contains("interior"));
  REQUIRE(t.warnings.size() == 3);
  CHECK_THAT(t.warnings[0], StartsWith("scene.xml:2:31: <medium type=\"rgbfog\">: unsupported medium plugin") &&
                                Contains("vacuum in its place"));
  CHECK_THAT(t.warnings[1], Contains("unsupported subsurface plugin \"dipole\"") && Contains("the shape's BSDF alone renders it"));
  CHECK_THAT(t.warnings[2], Contains("unsupported medium plugin") && Contains("vacuum in its place"));
}

TEST_CASE("mitsuba: files named in an included file: its folder, the scene's, then <path> folders", "[mitsuba]" TIER_UNIT) {
  // Issue 24, item 4: Mitsuba's resolver order, and <path> in an included file relative to it.
  test::TempDir dir;
  namespace fs = std::filesystem;
  fs::create_directories(dir.path() / "sub" / "tex");
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  dir.write("sub/near.obj", tri);      // next to the included file
  dir.write("main.obj", tri);          // next to the scene only
  dir.write("sub/tex/far.obj", tri);   // in the included file's <path> only
  dir.write("near.obj", tri);          // also next to the scene: the included file's own wins
  dir.write("sub/parts.xml", xml_scene(R"(  <path value="tex"/>
  <shape type="obj"><string name="filename" value="near.obj"/></shape>
  <shape type="obj"><string name="filename" value="main.obj"/></shape>
  <shape type="obj"><string name="filename" value="far.obj"/></shape>)"));
  const std::string main = dir.write("main.xml", loadable(R"(  <include filename="sub/parts.xml"/>)"));
  const json d = read_mitsuba(test::read_text(main), main, dir.path().string(), {}).doc;
  REQUIRE(d["objects"].size() == 3);
  CHECK(fs::equivalent(d["objects"][0]["file"].get<std::string>(), dir.path() / "sub" / "near.obj"));
  CHECK(fs::equivalent(d["objects"][1]["file"].get<std::string>(), dir.path() / "main.obj"));
  CHECK(fs::equivalent(d["objects"][2]["file"].get<std::string>(), dir.path() / "sub" / "tex" / "far.obj"));
}

TEST_CASE("mitsuba: rough BSDFs default to Beckmann as in Mitsuba; a given distribution is kept", "[mitsuba]" TIER_UNIT) {
  // Issue 24, item 10: JSON scenes default to GGX; Mitsuba's scenes meant Beckmann.
  for (const char* type : {"roughconductor", "roughdielectric", "roughplastic"}) {
    INFO(type);
    const json d = translate(xml_scene(std::string("  <bsdf type=\"") + type + "\" id=\"m\"/>\n  <bsdf type=\"" + type +
                                       "\" id=\"g\"><string name=\"distribution\" value=\"ggx\"/></bsdf>"));
    CHECK(d["materials"]["m"]["distribution"] == "beckmann");
    CHECK(d["materials"]["g"]["distribution"] == "ggx");
  }
  CHECK_FALSE(translate(xml_scene("  <bsdf type=\"conductor\" id=\"c\"/>"))["materials"]["c"].contains("distribution"));
}

TEST_CASE("mitsuba: sampling_weight of emitters and area emitters (samplingWeight in 0.6)", "[mitsuba]" TIER_UNIT) {
  const json d = translate(xml_scene(R"(  <emitter type="point"><float name="sampling_weight" value="3"/></emitter>
  <emitter type="area" id="e"><float name="sampling_weight" value="0.5"/></emitter>
  <shape type="sphere"><ref id="e"/></shape>)"));
  CHECK(d["lights"][0]["sampling_weight"] == 3.0);
  CHECK(d["objects"][0]["sampling_weight"] == 0.5);
  const json old = translate(xml_scene(R"(  <emitter type="point"><float name="samplingWeight" value="2"/></emitter>)", "0.6.0"));
  CHECK(old["lights"][0]["sampling_weight"] == 2.0);
}

TEST_CASE("mitsuba: dielectrics take specular_reflectance and specular_transmittance, as colours or textures", "[mitsuba]" TIER_UNIT) {
  // Issue 24: they were unknown keys of our dielectrics.
  const std::string xml = loadable(R"(  <bsdf type="dielectric" id="tinted"><rgb name="specular_transmittance" value="0.2, 0.8, 0.4"/></bsdf>
  <bsdf type="roughdielectric" id="frosted"><texture type="checkerboard" name="specular_reflectance"/></bsdf>
  <bsdf type="thindielectric" id="pane"><float name="specular_reflectance" value="0.5"/></bsdf>
  <shape type="sphere"><ref id="tinted"/></shape>
  <shape type="sphere"><point name="center" value="3, 0, 0"/><ref id="frosted"/></shape>
  <shape type="sphere"><point name="center" value="6, 0, 0"/><ref id="pane"/></shape>)");
  const LoadedScene loaded = parse_scene(xml, "scene.xml", ".");
  REQUIRE(loaded.scene->materials.size() >= 3);
  // The tint shows in the albedo photons are kept by: the larger of the two scales.
  const Bsdf* tinted = nullptr;
  for (size_t i = 0; i < loaded.scene->materials.size(); ++i) {
    if (loaded.scene->material_names[i] == "tinted") tinted = loaded.scene->materials[i].get();
  }
  REQUIRE(tinted != nullptr);
  CHECK(tinted->albedo() == Color(1.0f));
  const std::string bad = loadable(R"(  <bsdf type="dielectric" id="d"><rgb name="specular_transmittance" value="-1, 0, 0"/></bsdf>
  <shape type="sphere"><ref id="d"/></shape>)");
  CHECK_THAT(error_of([&] { parse_scene(bad, "scene.xml", "."); }), Contains("specular_transmittance"));
}

TEST_CASE("mitsuba: an area emitter's radiance as a texture", "[mitsuba]" TIER_UNIT) {
  // Issue 24: a textured area emitter was an error.
  const std::string xml = loadable(R"(  <shape type="rectangle">
    <emitter type="area"><texture type="checkerboard" name="radiance">
      <rgb name="color0" value="0.2, 0.4, 0.6"/><rgb name="color1" value="0, 0, 0"/></texture></emitter>
  </shape>)");
  const json d = translate(xml);
  const json& m = d["materials"][d["objects"][0]["material"].get<std::string>()];
  REQUIRE(m["emission"].is_object());
  CHECK(m["emission"]["type"] == "checkerboard");
  const LoadedScene loaded = parse_scene(xml, "scene.xml", ".");
  REQUIRE(loaded.scene->lights.size() == 1);
  // Half the rectangle emits color0: the power is pi A color0 / 2 (A = 4).
  CHECK(loaded.scene->lights[0]->power().z == Approx(kPi * 4.0 * 0.6 / 2.0).epsilon(0.01));
  // A value and a texture, or two textures: an error naming the place.
  CHECK_THAT(error_of([] {
               translate(xml_scene(R"(  <shape type="rectangle"><emitter type="area"><rgb name="radiance" value="1"/>
    <texture type="checkerboard" name="radiance"/></emitter></shape>)"));
             }),
             Contains("an area emitter takes one radiance"));
}

TEST_CASE("mitsuba: blendbsdf takes two nested BSDFs and a weight, a number or a texture", "[mitsuba]" TIER_UNIT) {
  const std::string xml = loadable(R"(  <bsdf type="blendbsdf" id="b"><float name="weight" value="0.25"/>
    <bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>
  <bsdf type="blendbsdf" id="t"><texture type="checkerboard" name="weight"/>
    <bsdf type="diffuse"/><bsdf type="plastic"/></bsdf>
  <shape type="sphere"><ref id="b"/></shape>
  <shape type="sphere"><point name="center" value="3, 0, 0"/><ref id="t"/></shape>)");
  const json d = translate(xml);
  CHECK(d["materials"]["b"]["type"] == "blendbsdf");
  CHECK(d["materials"]["b"]["bsdf"].size() == 2);
  CHECK(d["materials"]["b"]["weight"] == 0.25);
  const LoadedScene loaded = parse_scene(xml, "scene.xml", ".");
  const Bsdf* b = nullptr;
  for (size_t i = 0; i < loaded.scene->materials.size(); ++i) {
    if (loaded.scene->material_names[i] == "b") b = loaded.scene->materials[i].get();
  }
  REQUIRE(b != nullptr);
  // 0.75 of a 0.5 diffuse plus 0.25 of a perfect mirror.
  CHECK(b->albedo().x == Approx(0.75 * 0.5 + 0.25));
  CHECK_THAT(error_of([] { translate(xml_scene(R"(  <bsdf type="blendbsdf" id="x"><bsdf type="diffuse"/></bsdf>)")); }),
             Contains("takes two nested BSDFs"));
  const std::string heavy = loadable(R"(  <bsdf type="blendbsdf" id="h"><float name="weight" value="1.5"/>
    <bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>
  <shape type="sphere"><ref id="h"/></shape>)");
  CHECK_THAT(error_of([&] { parse_scene(heavy, "scene.xml", "."); }), Contains("weight must be one number in [0, 1]"));
}

TEST_CASE("mitsuba: normalmap nests one BSDF; a normal map that is not three channels is refused", "[mitsuba]" TIER_UNIT) {
  test::TempDir dir;
  Image normals(2, 2);
  for (Color& c : normals.pixels) c = Color(0.5f, 0.5f, 1.0f);
  write_image(dir.file("n.exr"), normals);
  {
    auto out = OIIO::ImageOutput::create(dir.file("grey.exr"));
    REQUIRE(out);
    const float texels[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    REQUIRE(out->open(dir.file("grey.exr"), OIIO::ImageSpec(2, 2, 1, OIIO::TypeDesc::FLOAT)));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, texels));
    REQUIRE(out->close());
  }
  auto scene = [&](const std::string& file) {
    return loadable(R"(  <bsdf type="normalmap" id="nm"><texture type="bitmap" name="normalmap"><string name="filename" value=")" +
                    file + R"("/><boolean name="raw" value="true"/></texture><bsdf type="diffuse"/></bsdf>
  <shape type="sphere"><ref id="nm"/></shape>)");
  };
  const LoadedScene ok = parse_scene(scene("n.exr"), dir.file("scene.xml"), dir.path().string());
  CHECK(ok.scene->materials.size() >= 2);
  CHECK_THAT(error_of([&] { parse_scene(scene("grey.exr"), dir.file("scene.xml"), dir.path().string()); }),
             Contains("a normal map needs three channels"));
}

TEST_CASE("mitsuba: bumpmap takes its height from its unnamed texture; a flat height leaves the image unchanged", "[mitsuba]" TIER_UNIT) {
  test::TempDir dir;
  Image flat(4, 4);
  for (Color& c : flat.pixels) c = Color(0.3f);
  write_image(dir.file("flat.exr"), flat);
  const std::string quad = R"(<shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/></transform>)";
  auto scene = [&](const std::string& bsdf) {
    return R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 3, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
      <rfilter type="box"/></film></sensor>
  <emitter type="point"><point name="position" x="0.5" y="2" z="0.5"/><rgb name="intensity" value="4"/></emitter>
)" + quad + bsdf + "</shape></scene>";
  };
  const std::string bumped = R"(<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="flat.exr"/></texture>
    <float name="scale" value="4"/><bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></bsdf>)";
  const std::string plain = R"(<bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf>)";
  const TranslatedScene t = read_mitsuba(scene(bumped), dir.file("scene.xml"), dir.path().string(), {});
  const json& m = t.doc["materials"].begin().value();
  CHECK(m["type"] == "bumpmap");
  CHECK(m["scale"] == 4.0);
  CHECK(m["height"]["type"] == "bitmap");
  CHECK(m["bsdf"]["type"] == "diffuse");
  auto render = [&](const std::string& bsdf) {
    LoadedScene s = parse_scene(scene(bsdf), dir.file("scene.xml"), dir.path().string());
    auto integ = create_integrator("path", JsonSource{}, s.scene->render);
    integ->preprocess(*s.scene, {1, true});
    RenderOptions options;
    options.job.passes = 2;
    options.quiet = true;
    RenderStats stats;
    return render_image(*s.scene, *integ, options, stats);
  };
  const Image a = render(bumped), b = render(plain);
  double mean = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    CHECK(a.pixels[i] == b.pixels[i]);
    mean += a.pixels[i].x;
  }
  CHECK(mean / double(a.pixels.size()) > 0.01);  // the quad is lit and seen
  CHECK_THAT(error_of([&] { translate(xml_scene(R"(  <bsdf type="bumpmap" id="x"><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>)")); }),
             Contains("takes one nested BSDF"));
  CHECK_THAT(error_of([&] {
               parse_scene(scene(R"(<bsdf type="bumpmap"><texture type="checkerboard"/><bsdf type="diffuse"/></bsdf>)"),
                           dir.file("scene.xml"), dir.path().string());
             }),
             Contains("a bump map's height texture must be a bitmap"));
}

TEST_CASE("mitsuba: principled and principledthin with numbers and textures", "[mitsuba]" TIER_UNIT) {
  const json doc = translate(xml_scene(R"(  <bsdf type="principled" id="p">
    <texture type="checkerboard" name="base_color"><rgb name="color0" value="0.1, 0.2, 0.3"/></texture>
    <texture type="checkerboard" name="roughness"/>
    <float name="metallic" value="0.3"/><float name="specular" value="0.6"/><float name="clearcoat" value="1"/>
    <float name="main_specular_sampling_rate" value="2"/>
  </bsdf>
  <bsdf type="principledthin" id="t"><float name="diff_trans" value="1.5"/><float name="eta" value="1.33"/></bsdf>)"));
  const json& p = doc["materials"]["p"];
  CHECK(p["type"] == "principled");
  CHECK(p["base_color"]["type"] == "checkerboard");
  CHECK(p["roughness"]["type"] == "checkerboard");
  CHECK(p["metallic"] == 0.3);
  CHECK(p["specular"] == 0.6);
  CHECK(p["main_specular_sampling_rate"] == 2.0);
  CHECK(doc["materials"]["t"]["diff_trans"] == 1.5);
  CHECK(doc["materials"]["t"]["eta"] == 1.33);
  // Loaded: the principled BSDF with its parameters; a bad one named where it is.
  const std::string bad = loadable(R"(  <bsdf type="principled" id="b"><float name="sheen" value="3"/></bsdf>
  <shape type="sphere"><ref id="b"/></shape>)");
  CHECK_THAT(error_of([&] { parse_scene(bad, "scene.xml", "."); }), Contains("sheen must be from 0 to 1"));
  CHECK_THAT(error_of([&] { parse_scene(bad, "scene.xml", "."); }), Contains("scene.xml:"));
}

TEST_CASE("mitsuba: 0.6's ward, coating and roughcoating with their camelCase names", "[mitsuba]" TIER_UNIT) {
  const json doc = translate(xml_scene(R"(  <bsdf type="coating" id="c"><float name="intIOR" value="1.7"/>
    <rgb name="sigmaA" value="0.1, 0.2, 0.3"/><float name="thickness" value="2"/><bsdf type="diffuse"/></bsdf>
  <bsdf type="roughcoating" id="r"><float name="alpha" value="0.3"/><bsdf type="diffuse"/></bsdf>
  <bsdf type="ward" id="w"><float name="alphaU" value="0.1"/><float name="alphaV" value="0.2"/>
    <string name="variant" value="ward-duer"/></bsdf>)", "0.6.0"));
  const json& c = doc["materials"]["c"];
  CHECK(c["type"] == "coating");
  CHECK(c["int_ior"] == 1.7);
  CHECK(c["thickness"] == 2.0);
  CHECK(c["sigma_a"].is_array());
  CHECK(c["bsdf"]["type"] == "diffuse");
  CHECK(doc["materials"]["r"]["distribution"] == "beckmann");  // Mitsuba's default
  CHECK(doc["materials"]["w"]["alpha_u"] == 0.1);
  CHECK(doc["materials"]["w"]["variant"] == "ward-duer");
  CHECK_THAT(error_of([] { translate(xml_scene(R"(  <bsdf type="coating" id="x"><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>)")); }),
             Contains("takes one nested BSDF"));
}

TEST_CASE("mitsuba: a spot's texture and a projector", "[mitsuba]" TIER_UNIT) {
  const json doc = translate(xml_scene(R"(  <emitter type="spot"><transform name="to_world"><lookat origin="0, 5, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
    <texture type="checkerboard" name="texture"/></emitter>
  <emitter type="projector"><transform name="to_world"><lookat origin="1, 2, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <texture type="checkerboard" name="irradiance"/><float name="scale" value="3"/><string name="focal_length" value="35mm"/></emitter>)"));
  const json& spot = doc["lights"][0];
  CHECK(spot["type"] == "spot");
  CHECK(spot["texture"]["type"] == "checkerboard");
  CHECK(spot["up"][2].get<double>() == Approx(1.0));
  const json& proj = doc["lights"][1];
  CHECK(proj["type"] == "projector");
  CHECK(proj["irradiance"]["type"] == "checkerboard");
  CHECK(proj["scale"] == 3.0);
  CHECK(proj["fov_axis"] == "diagonal");
  CHECK(proj["fov"].get<double>() == Approx(2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / 70.0) * 180.0 / 3.14159265358979));
  // fov_axis without fov: Mitsuba measures its default angle diagonally all the same.
  const json d2 = translate(xml_scene(R"(  <emitter type="projector"><string name="fov_axis" value="y"/></emitter>)"));
  CHECK_FALSE(d2["lights"][0].contains("fov_axis"));
  CHECK_THAT(error_of([] { translate(xml_scene(R"(  <emitter type="point"><texture type="checkerboard" name="texture"/></emitter>)")); }),
             Contains("<texture"));
}

TEST_CASE("mitsuba: a <path> in an included file that is not next to it is resolved from the scene's folder", "[mitsuba]" TIER_UNIT) {
  // Mitsuba's own documentation scenes: docs/scenes/include/emitter_scene.xml says
  // <path value="../../common"/>, which exists from docs/scenes (the scene's folder), not from
  // docs/scenes/include. Mitsuba 3 tries the file's folder, then its file resolver.
  test::TempDir dir;
  namespace fs = std::filesystem;
  fs::create_directories(dir.path() / "docs" / "scenes" / "include");
  fs::create_directories(dir.path() / "common");
  dir.write("common/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  dir.write("docs/scenes/include/parts.xml", xml_scene(R"(  <path value="../../common"/>
  <shape type="obj"><string name="filename" value="tri.obj"/></shape>)"));
  const std::string main = dir.write("docs/scenes/main.xml", loadable(R"(  <include filename="include/parts.xml"/>)"));
  const json d = read_mitsuba(test::read_text(main), main, (dir.path() / "docs" / "scenes").string(), {}).doc;
  REQUIRE(d["objects"].size() == 1);
  CHECK(fs::equivalent(d["objects"][0]["file"].get<std::string>(), dir.path() / "common" / "tri.obj"));
  // A folder found nowhere names every place tried.
  dir.write("docs/scenes/include/bad.xml", xml_scene(R"(  <path value="../../nowhere"/>)"));
  const std::string bad = dir.write("docs/scenes/bad.xml", loadable(R"(  <include filename="include/bad.xml"/>)"));
  CHECK_THAT(error_of([&] { read_mitsuba(test::read_text(bad), bad, (dir.path() / "docs" / "scenes").string(), {}); }),
             Contains("the folder does not exist: tried") && Contains("include/../../nowhere") && Contains("scenes/../../nowhere"));
}

TEST_CASE("mitsuba: plugin names in any case (\"Rectangle\" from exported scenes); a bump map's texture by any name", "[mitsuba]" TIER_UNIT) {
  const json d = translate(xml_scene(R"(  <shape type="Sphere"/>
  <bsdf type="BumpMap" id="b"><texture type="checkerboard" name="tiles_bump"/><bsdf type="Diffuse"/></bsdf>)"));
  CHECK(d["objects"][0]["type"] == "sphere");
  CHECK(d["materials"]["b"]["type"] == "bumpmap");
  CHECK(d["materials"]["b"]["height"]["type"] == "checkerboard");
  CHECK(d["materials"]["b"]["bsdf"]["type"] == "diffuse");
}

TEST_CASE("mitsuba: a sampler declared at the top level with an id and referred to from the sensor", "[mitsuba]" TIER_UNIT) {
  // Mitsuba's documentation scenes declare <sampler type="..." id="my_sampler"> beside the sensor.
  const json d = translate(xml_scene(R"(  <sampler type="multijitter" id="s"><integer name="sample_count" value="16"/></sampler>
  <sensor type="perspective"><ref id="s"/></sensor>)"));
  CHECK(d["render"]["spp"] == 16);
}

TEST_CASE("mitsuba: homogeneous media, their phase functions and constant volumes become our media; shapes' "
          "interior and exterior and the sensor's medium refer to them",
          "[mitsuba][media]" TIER_UNIT) {
  const std::string body = R"(
  <medium type="homogeneous" id="fog">
    <rgb name="sigma_t" value="0.5, 1, 2"/>
    <volume type="constvolume" name="albedo"><float name="value" value="0.8"/></volume>
    <float name="scale" value="2"/>
    <phase type="hg"><float name="g" value="0.5"/></phase>
  </medium>
  <medium type="homogeneous" id="unused"/>
  <shape type="sphere">
    <float name="radius" value="1"/>
    <bsdf type="null"/>
    <ref name="interior" id="fog"/>
    <medium type="homogeneous" name="exterior"><float name="sigma_t" value="0.1"/></medium>
  </shape>)";
  const std::string xml = xml_scene(R"(  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0, 0, 10" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    <ref id="fog"/>
  </sensor>)" + body);
  const json doc = translate(xml);
  INFO(doc.dump());
  REQUIRE(doc.contains("media"));
  CHECK(doc["media"].size() == 2);  // the one nothing refers to is left out
  const json& fog = doc["media"]["fog"];
  check_vec(fog["sigma_t"], {0.5, 1.0, 2.0});
  CHECK(fog["albedo"] == 0.8);
  CHECK(fog["scale"] == 2.0);
  CHECK(fog["phase"]["type"] == "hg");
  CHECK(fog["phase"]["g"] == 0.5);
  CHECK(doc["camera"]["medium"] == "fog");
  CHECK(doc["objects"][0]["interior"] == "fog");
  const std::string outside = doc["objects"][0]["exterior"];
  CHECK(doc["media"][outside]["sigma_t"] == 0.1);
  // The scene loads: the medium table checks the values.
  const LoadedScene loaded = parse_scene(xml, "scene.xml", ".");
  CHECK(loaded.scene->media.size() == 2);
  CHECK(loaded.scene->camera_medium >= 0);
  CHECK(loaded.scene->has_media());
  // A grid in a homogeneous medium: an error naming it (Mitsuba's homogeneous takes constants).
  const std::string grid = xml_scene(R"(<shape type="sphere"><bsdf type="null"/>
    <medium type="homogeneous" name="interior"><volume type="gridvolume" name="sigma_t"><string name="filename" value="a.vol"/></volume></medium>
  </shape>)");
  CHECK_THAT(error_of([&] { translate(grid); }), Catch::Contains("scene.xml") && Catch::Contains("gridvolume") &&
                                                     Catch::Contains("supported: constvolume"));
  CHECK_THAT(error_of([&] { parse_scene(loadable(R"(<shape type="sphere"><bsdf type="null"/>
    <medium type="homogeneous" name="interior"><float name="sigma_t" value="-1"/></medium></shape>)"), "scene.xml", "."); }),
             Catch::Contains("scene.xml:") && Catch::Contains("sigma_t"));
  CHECK_THAT(error_of([&] { parse_scene(loadable(R"(<shape type="sphere"><bsdf type="null"/>
    <medium type="homogeneous" name="interior"><float name="albedo" value="1.5"/></medium></shape>)"), "scene.xml", "."); }),
             Catch::Contains("scene.xml:") && Catch::Contains("albedo") && Catch::Contains("[0, 1]"));
}

TEST_CASE("mitsuba: heterogeneous media read grid and constant volumes placed as Mitsuba 3 places them: the unit "
          "cube under to_world (or the file's box), values at cell centres; the medium is empty outside that box",
          "[mitsuba][media]" TIER_UNIT) {
  test::TempDir dir;
  // A 2 x 1 x 1 grid: 1 in its low-x voxel, 3 in its high-x one.
  VolumeGrid g = test::make_grid(2, 1, 1, Vec3(-5.0f), Vec3(5.0f), [](int x, int, int) { return 1.0f + 2.0f * float(x); });
  dir.write("two.vol", format_vol(g));
  g.values = {0.5f, 0.8f};
  dir.write("albedo.vol", format_vol(g));
  const std::string body = R"(
  <shape type="cube">
    <transform name="to_world"><scale value="4"/></transform>
    <bsdf type="null"/>
    <medium type="heterogeneous" name="interior">
      <float name="scale" value="0.5"/>
      <volume type="gridvolume" name="sigma_t">
        <string name="filename" value="two.vol"/>
        <transform name="to_world"><scale x="2" y="1" z="1"/><translate x="-1" y="-0.5" z="-0.5"/></transform>
      </volume>
      <volume type="gridvolume" name="albedo">
        <string name="filename" value="albedo.vol"/><boolean name="use_grid_bbox" value="true"/>
        <string name="filter_type" value="nearest"/>
      </volume>
    </medium>
  </shape>
  <shape type="sphere">
    <point name="center" x="20" y="0" z="0"/>
    <bsdf type="null"/>
    <medium type="heterogeneous" name="interior">
      <volume type="constvolume" name="sigma_t"><float name="value" value="2"/>
        <transform name="to_world"><translate x="19.5" y="-0.5" z="-0.5"/></transform></volume>
    </medium>
  </shape>)";
  const std::string path = dir.write("scene.xml", loadable(body));
  const json d = read_mitsuba(test::read_text(path), path, dir.path().string(), {}).doc;
  INFO(d["media"].dump());
  REQUIRE(d["media"].size() == 2);
  // (The scene's media are the JSON block's in its key order: the grid's name sorts first.)
  const std::string grid_name = d["objects"][0]["interior"], flat_name = d["objects"][1]["interior"];
  REQUIRE(grid_name < flat_name);
  const json& grid = d["media"][grid_name];
  CHECK(grid["type"] == "heterogeneous");
  CHECK(grid["sigma_t"]["type"] == "gridvolume");
  CHECK(grid["sigma_t"]["voxels"] == "centres");
  CHECK(grid["sigma_t"]["box"] == "unit");
  CHECK(grid["albedo"]["box"] == "file");
  CHECK(grid["albedo"]["filter"] == "nearest");
  const json& flat = d["media"][flat_name];
  CHECK(flat["sigma_t"]["type"] == "constvolume");
  CHECK(flat["sigma_t"]["to_world"][0][3] == 19.5);
  // Transmittance along x through each (ratio tracking, averaged): the grid's voxels sit at the
  // centres of the two halves of [-1, 1] (x = -0.5 and 0.5; sigma_t 0.5 and 1.5), a ramp between
  // them and held beyond: optical depth 0.25 + 1 + 0.75 = 2 over the box, nothing outside it
  // though the cube spans [-4, 4]. The constant fills only the unit cube at 19.5..20.5 of the
  // sphere [19, 21]: optical depth 2 as well.
  const LoadedScene loaded = parse_scene(test::read_text(path), path, dir.path().string());
  const Scene& scene = *loaded.scene;
  REQUIRE(scene.media.size() == 2);
  Sampler sampler(3);
  auto mean_tr = [&](const Medium& m, const Ray& ray) {
    double sum = 0;
    for (int i = 0; i < 40000; ++i) sum += m.transmittance(ray, 20.0f, sampler).x;
    return sum / 40000;
  };
  const Ray through{Vec3(-10.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), kInfinity};
  CHECK(mean_tr(*scene.media[0], through) == Approx(std::exp(-2.0)).epsilon(0.03));
  const Ray far{Vec3(10.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), kInfinity};
  CHECK(mean_tr(*scene.media[1], far) == Approx(std::exp(-2.0)).epsilon(0.03));
  // The medium's bounds: a ray missing the unit box under to_world passes untouched.
  const Ray beside{Vec3(-10.0f, 0.7f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), kInfinity};
  CHECK(scene.media[0]->transmittance(beside, 20.0f, sampler).x == 1.0f);
  // Mitsuba's wrap modes other than clamp are refused by name.
  const std::string wrapped = dir.write("wrapped.xml", xml_scene(R"(<shape type="sphere"><bsdf type="null"/><medium type="heterogeneous" name="interior">
      <volume type="gridvolume" name="sigma_t"><string name="filename" value="two.vol"/><string name="wrap_mode" value="repeat"/></volume>
    </medium></shape>)"));
  CHECK_THAT(error_of([&] { read_mitsuba(test::read_text(wrapped), wrapped, dir.path().string(), {}); }),
             Contains("wrapped.xml:3:") && Contains("wrap_mode"));
}
