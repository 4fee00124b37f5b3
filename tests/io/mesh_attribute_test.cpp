// Mesh attributes (issue 24): PLY vertex and face properties grouped and converted as
// Mitsuba 3's PLY reader does, and the mesh_attribute texture that reads them at a hit.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include <cstring>
#include "core/scene.h"
#include "io/meshes/mesh_file.h"
#include "io/scene_loader.h"
#include "support/errors.h"
#include "support/temp_dir.h"

using namespace caustica;
using Catch::Matchers::Contains;
using test::error_of;

namespace {

// The sRGB decoding, written out here in double precision.
double decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

void check_colour(const Color& got, double r, double g, double b) {
  INFO("got " << got.x << " " << got.y << " " << got.z << ", expected " << r << " " << g << " " << b);
  CHECK(got.x == Approx(r).margin(1e-6));
  CHECK(got.y == Approx(g).margin(1e-6));
  CHECK(got.z == Approx(b).margin(1e-6));
}

const MeshAttribute& attribute(const MeshData& m, const std::string& name) {
  const MeshAttribute* a = m.extra.find(name);
  INFO("attribute " << name);
  REQUIRE(a != nullptr);
  return *a;
}

template <class T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

}  // namespace

TEST_CASE("mesh attributes: PLY properties are grouped and named as Mitsuba's reader does", "[mesh][texture]" TIER_UNIT) {
  // Vertex: red green blue (alpha dropped) make vertex_color; foo_x/y/z vertex_foo; bar_0 a
  // one-channel vertex_bar; two fields (baz_r baz_g), a postfix that cannot start a run (n_q)
  // and names without a postfix are skipped. Face: r g b make face_color, id_1 face_id.
  const std::string ply = R"(ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
property uchar red
property uchar green
property uchar blue
property uchar alpha
property float foo_x
property float foo_y
property float foo_z
property float bar_0
property float baz_r
property float baz_g
property float n_q
property float plain
element face 2
property list uchar int vertex_indices
property float id_1
property uchar r
property uchar g
property uchar b
end_header
0 0 0 255 0 128 7 1 2 3 0.5 9 9 9 9
1 0 0 0 255 0 7 4 5 6 1.5 9 9 9 9
1 1 0 0 0 255 7 7 8 9 2.5 9 9 9 9
0 1 0 51 102 204 7 10 11 12 3.5 9 9 9 9
4 0 1 2 3 0.25 255 0 0
3 0 1 3 0.75 0 0 255
)";
  const MeshData m = parse_ply(ply, "attrs.ply");
  REQUIRE(m.tris.size() == 3);  // the quad's fan, then the triangle
  std::vector<std::string> names;
  for (const MeshAttribute& a : m.extra.list) names.push_back(a.name);
  CHECK(names == std::vector<std::string>{"vertex_color", "vertex_foo", "vertex_bar", "face_color", "face_id"});

  // Integers are normalised and decoded from sRGB; floats are taken as they are.
  const MeshAttribute& colour = attribute(m, "vertex_color");
  CHECK(colour.channels == 3);
  CHECK_FALSE(colour.per_face);
  REQUIRE(colour.values.size() == 9);
  check_colour(colour.values[0], 1.0, 0.0, decode(128.0 / 255.0));                         // triangle 0, vertex 0
  check_colour(colour.values[5], decode(0.2), decode(0.4), decode(0.8));                   // triangle 1, vertex 3
  check_colour(colour.values[7], 0.0, 1.0, 0.0);                                           // triangle 2, vertex 1
  const MeshAttribute& foo = attribute(m, "vertex_foo");
  CHECK(foo.values[2] == Color(7, 8, 9));  // triangle 0, vertex 2
  const MeshAttribute& bar = attribute(m, "vertex_bar");
  CHECK(bar.channels == 1);
  CHECK(bar.values[5] == Color(3.5f));  // triangle 1, vertex 3, as a grey
  const MeshAttribute& face = attribute(m, "face_color");
  CHECK(face.per_face);
  REQUIRE(face.values.size() == 3);
  CHECK(face.values[0] == Color(1, 0, 0));
  CHECK(face.values[1] == Color(1, 0, 0));  // the quad's second triangle shares its face's value
  CHECK(face.values[2] == Color(0, 0, 1));
  const MeshAttribute& id = attribute(m, "face_id");
  CHECK(id.channels == 1);
  CHECK(id.values == std::vector<Color>{Color(0.25f), Color(0.25f), Color(0.75f)});
  // The value at barycentrics: interpolated for a vertex attribute, constant for a face one.
  const Vec3 b(0.5f, 0.25f, 0.25f);
  const Color expected = 0.5f * foo.values[3] + 0.25f * foo.values[4] + 0.25f * foo.values[5];
  CHECK(glm::length(foo.at(1, b) - expected) < 1e-6f);
  CHECK(id.at(2, b) == Color(0.75f));
}

TEST_CASE("mesh attributes: binary PLY integers of every width normalise as Mitsuba's do", "[mesh][texture]" TIER_UNIT) {
  // ushort w_x over 65535, signed char s_x over 127 (negative values keep their sign).
  std::string ply =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property ushort w_x\nproperty char s_x\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  auto be = [&](auto v) {
    char b[sizeof(v)];
    std::memcpy(b, &v, sizeof(v));
    for (size_t i = sizeof(v); i-- > 0;) ply.push_back(b[i]);
  };
  const float pos[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const uint16_t w[3] = {65535, 32768, 0};
  const int8_t s[3] = {-127, 127, 0};
  for (int i = 0; i < 3; ++i) {
    for (float c : pos[i]) be(c);
    be(w[i]);
    be(s[i]);
  }
  be(uint8_t(3));
  for (uint32_t i : {0u, 1u, 2u}) be(i);
  const MeshData m = parse_ply(ply, "be.ply");
  const MeshAttribute& wa = attribute(m, "vertex_w");
  CHECK(wa.values[0] == Color(1.0f));
  CHECK(wa.values[1].x == Approx(decode(32768.0 / 65535.0)).margin(1e-6));
  CHECK(wa.values[2] == Color(0.0f));
  const MeshAttribute& sa = attribute(m, "vertex_s");
  CHECK(sa.values[0] == Color(-1.0f));
  CHECK(sa.values[1] == Color(1.0f));
}

TEST_CASE("mesh attributes: a PLY with two face elements is an error (their attributes would not line up)", "[mesh][texture]" TIER_UNIT) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty uchar r\nproperty uchar g\nproperty uchar b\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 2 3\n3 0 2 1\n";
  CHECK(error_of([&] { parse_ply(ply, "two.ply"); }) == "two.ply:19: a second face element");
}

TEST_CASE("mesh attributes: a non-finite property is an error naming the element", "[mesh][texture]" TIER_UNIT) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property float q_x\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1\n1 0 0 nan\n0 1 0 1\n3 0 1 2\n";
  CHECK(error_of([&] { parse_ply(ply, "nan.ply"); }) == "nan.ply:12: vertex 1: property q_x is not finite");
}

namespace {

// A scene of two PLY triangles in z = 0, one with vertex colours (float) and one with a face
// colour, and a sphere; each object's material reads an attribute through mesh_attribute.
struct AttributeScene {
  test::TempDir dir;
  std::string path;
  explicit AttributeScene(const std::string& materials) {
    dir.write("v.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "property float red\nproperty float green\nproperty float blue\n"
                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0 0.8 0.1 0.2\n1 0 0 0.3 0.6 0.05\n0 1 0 0.1 0.2 0.9\n3 0 1 2\n");
    dir.write("f.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list uchar int vertex_indices\nproperty uchar r\nproperty uchar g\n"
                       "property uchar b\nend_header\n2 0 0\n3 0 0\n2 1 0\n3 0 1 2 255 51 0\n");
    path = dir.write("scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": )" + materials + R"(,
      "objects": [{"type": "mesh", "file": "v.ply", "material": "a"},
                  {"type": "mesh", "file": "f.ply", "material": "b"},
                  {"type": "sphere", "center": [-3, 0, 0], "radius": 1, "material": "a"}],
      "lights": [{"type": "point", "position": [0, 0, 3], "intensity": 1}]})");
  }
};

Color albedo_at(const Scene& s, const Vec3& origin) {
  SurfaceHit hit;
  REQUIRE(s.intersect(Ray{origin, Vec3(0, 0, -1), kInfinity}, hit));
  return hit.material->albedo(hit.sp);
}

}  // namespace

TEST_CASE("mesh attributes: the texture reads the hit triangle's values, interpolated or per face", "[mesh][texture]" TIER_UNIT) {
  const AttributeScene scene(R"({
      "a": {"type": "diffuse", "reflectance": {"type": "mesh_attribute", "name": "vertex_color", "scale": 0.5}},
      "b": {"type": "diffuse", "reflectance": {"type": "mesh_attribute", "name": "face_color"}}})");
  const LoadedScene loaded = load_scene(scene.path);
  const Scene& s = *loaded.scene;
  // At (0.25, 0.25) the barycentrics are (0.5, 0.25, 0.25).
  check_colour(albedo_at(s, Vec3(0.25f, 0.25f, 1)), 0.5 * (0.5 * 0.8 + 0.25 * 0.3 + 0.25 * 0.1),
               0.5 * (0.5 * 0.1 + 0.25 * 0.6 + 0.25 * 0.2), 0.5 * (0.5 * 0.2 + 0.25 * 0.05 + 0.25 * 0.9));
  check_colour(albedo_at(s, Vec3(0.1f, 0.7f, 1)), 0.5 * (0.2 * 0.8 + 0.1 * 0.3 + 0.7 * 0.1),
               0.5 * (0.2 * 0.1 + 0.1 * 0.6 + 0.7 * 0.2), 0.5 * (0.2 * 0.2 + 0.1 * 0.05 + 0.7 * 0.9));
  // The face's colour anywhere on it (uchar: decoded from sRGB).
  check_colour(albedo_at(s, Vec3(2.2f, 0.3f, 1)), 1.0, decode(0.2), 0.0);
  check_colour(albedo_at(s, Vec3(2.6f, 0.1f, 1)), 1.0, decode(0.2), 0.0);
  // A sphere carries no attributes: black.
  check_colour(albedo_at(s, Vec3(-3, 0, 5)), 0, 0, 0);
}

TEST_CASE("mesh attributes: bad names and attributes no mesh carries are errors at their place", "[mesh][texture]" TIER_UNIT) {
  const AttributeScene prefix(R"({"a": {"type": "diffuse", "reflectance": {"type": "mesh_attribute", "name": "color"}},
      "b": {"type": "diffuse"}})");
  CHECK_THAT(error_of([&] { load_scene(prefix.path); }),
             Contains("/materials/a/reflectance/name") && Contains("must start with \"vertex_\" or \"face_\", not \"color\""));
  const AttributeScene missing(R"({"a": {"type": "diffuse"},
      "b": {"type": "diffuse", "reflectance": {"type": "mesh_attribute", "name": "vertex_normal_map"}}})");
  CHECK_THAT(error_of([&] { load_scene(missing.path); }),
             Contains("/materials/b/reflectance/name") &&
                 Contains("no mesh in the scene carries the attribute \"vertex_normal_map\" (the meshes carry: face_color, vertex_color)"));
}

TEST_CASE("mesh attributes: a light's texture cannot be a mesh attribute", "[mesh][texture]" TIER_UNIT) {
  test::TempDir dir;
  dir.write("v.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "property float red\nproperty float green\nproperty float blue\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                     "0 0 0 0.8 0.1 0.2\n1 0 0 0.3 0.6 0.05\n0 1 0 0.1 0.2 0.9\n3 0 1 2\n");
  const std::string path = dir.write("s.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"a": {"type": "diffuse", "reflectance": {"type": "mesh_attribute", "name": "vertex_color"}}},
      "objects": [{"type": "mesh", "file": "v.ply", "material": "a"}],
      "lights": [{"type": "spot", "position": [0, 0, 3], "target": [0, 0, 0], "intensity": 1,
                  "texture": {"type": "mesh_attribute", "name": "vertex_color"}}]})");
  CHECK_THAT(error_of([&] { load_scene(path); }),
             Contains("/lights/0/texture") && Contains("a light's texture has no mesh"));
}

TEST_CASE("mesh attributes: values beyond what a colour may hold are an error at load", "[mesh][texture]" TIER_UNIT) {
  // 2e8 times a scale of 10 passes 1e9 (the cap on every colour and emission).
  const AttributeScene scene(R"({"a": {"type": "diffuse"},
      "b": {"type": "diffuse", "reflectance": {"type": "mesh_attribute", "name": "face_color", "scale": 5e3}}})");
  scene.dir.write("f.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nproperty float r\nproperty float g\n"
                     "property float b\nend_header\n2 0 0\n3 0 0\n2 1 0\n3 0 1 2 1 2e5 0\n");
  CHECK_NOTHROW(load_scene(scene.path));
  scene.dir.write("f.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nproperty float r\nproperty float g\n"
                     "property float b\nend_header\n2 0 0\n3 0 0\n2 1 0\n3 0 1 2 1 2e8 0\n");
  CHECK_THAT(error_of([&] { load_scene(scene.path); }),
             Contains("/materials/b/reflectance/name") &&
                 Contains("the attribute \"face_color\" reaches 1e+12 (times scale), beyond the 1e+09 a colour may hold"));
}

TEST_CASE("mesh attributes: Mitsuba scenes read mesh_attribute textures, errors name the XML line", "[mesh][texture][mitsuba]" TIER_UNIT) {
  test::TempDir dir;
  dir.write("v.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "property float red\nproperty float green\nproperty float blue\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                     "0 0 0 0.8 0.1 0.2\n1 0 0 0.3 0.6 0.05\n0 1 0 0.1 0.2 0.9\n3 0 1 2\n");
  auto scene = [&](const std::string& attribute) {
    return dir.write("s.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform></sensor>
  <emitter type="point"><point name="position" x="0" y="0" z="3"/></emitter>
  <shape type="ply">
    <string name="filename" value="v.ply"/>
    <bsdf type="diffuse">
      <texture type="mesh_attribute" name="reflectance">
        <string name="name" value=")" + attribute + R"("/>
        <float name="scale" value="2"/>
      </texture>
    </bsdf>
  </shape>
</scene>
)");
  };
  const LoadedScene loaded = load_scene(scene("vertex_color"));
  check_colour(albedo_at(*loaded.scene, Vec3(0.25f, 0.25f, 1)), 2 * (0.5 * 0.8 + 0.25 * 0.3 + 0.25 * 0.1),
               2 * (0.5 * 0.1 + 0.25 * 0.6 + 0.25 * 0.2), 2 * (0.5 * 0.2 + 0.25 * 0.05 + 0.25 * 0.9));
  const std::string path = scene("face_color");
  CHECK_THAT(error_of([&] { load_scene(path); }),
             Contains(path + ":8") && Contains("no mesh in the scene carries the attribute \"face_color\""));
}
