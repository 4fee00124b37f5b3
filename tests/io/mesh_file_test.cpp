// Mesh files: OBJ, ASCII and binary PLY, Mitsuba .serialized (one and several shapes) read back
// exactly; broken files (truncated, non-finite numbers, a shape_index out of range) are errors
// naming the file; an OBJ's .mtl gives a JSON scene its materials and area lights.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <zlib.h>
#include "core/lights/area.h"
#include "io/json_reader.h"
#include "io/meshes/mesh_file.h"
#include "io/scene_loader.h"
#include "support/errors.h"
#include "support/run.h"
#include "support/temp_dir.h"

using namespace caustica;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

using test::error_of;

template <class T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

// A quad as two triangles, with a normal, a UV and a position per vertex that all differ.
struct Quad {
  std::vector<Vec3> pos = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0.5f}, {0, 1, 0.5f}};
  std::vector<Vec3> normals = {{0, 0, 1}, {0, 0.5f, 0.75f}, {0.25f, 0, 1}, {-0.5f, 0.125f, 1}};
  std::vector<Vec2> uvs = {{0, 0}, {1, 0}, {1, 0.75f}, {0.125f, 0.25f}};
  std::vector<glm::ivec3> tris = {{0, 1, 2}, {0, 2, 3}};
};

// Every triangle's corners have the expected position, normal and UV (`flip_v`: 1 - v).
// The quad's four vertices in order and its two triangles as written.
void check_indexed_quad(const MeshData& m, const Quad& q) {
  REQUIRE(m.verts.size() == 4);
  for (size_t i = 0; i < 4; ++i) CHECK(m.verts[i] == q.pos[i]);
  REQUIRE(m.tris.size() == 2);
  CHECK(m.tris[0] == glm::ivec3(0, 1, 2));
  CHECK(m.tris[1] == glm::ivec3(0, 2, 3));
}

void check_quad(const MeshData& m, const Quad& q, bool normals, bool uvs, bool flip_v) {
  REQUIRE(m.tris.size() == q.tris.size());
  if (normals || uvs) REQUIRE(m.attributes.size() == q.tris.size());
  for (size_t t = 0; t < q.tris.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      INFO("triangle " << t << " corner " << k);
      const int i = q.tris[t][k];
      REQUIRE(m.tris[t][k] >= 0);
      REQUIRE(size_t(m.tris[t][k]) < m.verts.size());
      CHECK(m.verts[size_t(m.tris[t][k])] == q.pos[size_t(i)]);
      if (normals) {
        CHECK(m.attributes[t].has_normals);
        CHECK(m.attributes[t].n[k] == q.normals[size_t(i)]);
      }
      if (uvs) {
        CHECK(m.attributes[t].has_uvs);
        const Vec2 uv = q.uvs[size_t(i)];
        CHECK(m.attributes[t].uv[k] == (flip_v ? Vec2(uv.x, 1.0f - uv.y) : uv));
      }
    }
  }
}

std::string ply_header(const char* format, int vertices, int faces, bool attributes = true) {
  std::string h = std::string("ply\nformat ") + format + " 1.0\ncomment test\nelement vertex " + std::to_string(vertices) +
                  "\nproperty float x\nproperty float y\nproperty float z\n";
  if (attributes) h += "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n";
  h += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
  return h;
}

std::string binary_ply(const Quad& q) {
  std::string s = ply_header("binary_little_endian", 4, 2);
  for (size_t i = 0; i < 4; ++i) {
    for (int c = 0; c < 3; ++c) put<float>(s, q.pos[i][c]);
    for (int c = 0; c < 3; ++c) put<float>(s, q.normals[i][c]);
    put<float>(s, q.uvs[i].x);
    put<float>(s, q.uvs[i].y);
  }
  for (const glm::ivec3& t : q.tris) {
    put<uint8_t>(s, 3);
    for (int k = 0; k < 3; ++k) put<int32_t>(s, t[k]);
  }
  return s;
}

// One shape of a .serialized file: header and zlib stream.
struct SerializedShape {
  std::string name;
  std::vector<float> pos, normals, uvs, colours;
  std::vector<uint32_t> indices;
  uint64_t vertex_count() const { return pos.size() / 3; }
};

std::string compress(const std::string& raw) {
  uLongf size = compressBound(uLong(raw.size()));
  std::string out(size, '\0');
  REQUIRE(compress2(reinterpret_cast<Bytef*>(&out[0]), &size, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()),
                    Z_BEST_COMPRESSION) == Z_OK);
  out.resize(size);
  return out;
}

std::string serialized_raw(const SerializedShape& s, uint64_t vertex_count, uint64_t triangle_count) {
  std::string raw;
  uint32_t flags = 0x1000;
  if (!s.normals.empty()) flags |= 0x0001;
  if (!s.uvs.empty()) flags |= 0x0002;
  if (!s.colours.empty()) flags |= 0x0008;
  put<uint32_t>(raw, flags);
  raw += s.name;
  raw += '\0';
  put<uint64_t>(raw, vertex_count);
  put<uint64_t>(raw, triangle_count);
  for (float f : s.pos) put<float>(raw, f);
  for (float f : s.normals) put<float>(raw, f);
  for (float f : s.uvs) put<float>(raw, f);
  for (float f : s.colours) put<float>(raw, f);
  for (uint32_t i : s.indices) put<uint32_t>(raw, i);
  return raw;
}

std::string serialized_blob(const std::string& raw) {
  std::string blob;
  put<uint16_t>(blob, 0x041C);
  put<uint16_t>(blob, 4);
  return blob + compress(raw);
}

std::string serialized_shape(const SerializedShape& s) {
  return serialized_blob(serialized_raw(s, s.vertex_count(), s.indices.size() / 3));
}

// Several shapes, then the table: uint64 offset per shape and a uint32 count.
std::string serialized_file(const std::vector<SerializedShape>& shapes) {
  std::string file;
  std::vector<uint64_t> offsets;
  for (const SerializedShape& s : shapes) {
    offsets.push_back(file.size());
    file += serialized_shape(s);
  }
  for (uint64_t o : offsets) put<uint64_t>(file, o);
  put<uint32_t>(file, uint32_t(shapes.size()));
  return file;
}

SerializedShape quad_shape(const Quad& q) {
  SerializedShape s;
  s.name = "quad";
  for (size_t i = 0; i < 4; ++i) {
    for (int c = 0; c < 3; ++c) s.pos.push_back(q.pos[i][c]);
    for (int c = 0; c < 3; ++c) s.normals.push_back(q.normals[i][c]);
    s.uvs.push_back(q.uvs[i].x);
    s.uvs.push_back(q.uvs[i].y);
  }
  for (const glm::ivec3& t : q.tris) {
    for (int k = 0; k < 3; ++k) s.indices.push_back(uint32_t(t[k]));
  }
  return s;
}

SerializedShape triangle_shape() {
  SerializedShape s;
  s.name = "tri";
  s.pos = {5, 0, 0, 6, 0, 0, 5, 3, -1};
  s.indices = {0, 2, 1};
  return s;
}

}  // namespace

TEST_CASE("mesh files: OBJ positions, indices, normals and flipped UVs read back exactly", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  const Quad q;
  const std::string path = dir.write("quad.obj", R"(# a quad as two triangles
v 0 0 0
v 2 0 0
v 2 1 0.5
v 0 1 0.5
vt 0 0
vt 1 0
vt 1 0.75
vt 0.125 0.25
vn 0 0 1
vn 0 0.5 0.75
vn 0.25 0 1
vn -0.5 0.125 1
f 1/1/1 2/2/2 3/3/3
f 1/1/1 3/3/3 4/4/4
)");
  const MeshData m = read_mesh_file(path);
  check_indexed_quad(m, q);
  check_quad(m, q, true, true, true);  // OBJ's v points up: 1 - v
  CHECK(m.materials.empty());
  CHECK(m.material_ids.empty());

  // Without vn and vt there are no attributes; a polygon is triangulated.
  const MeshData plain = read_mesh_file(dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  CHECK(plain.tris.size() == 2);
  CHECK(plain.attributes.empty());
}

TEST_CASE("mesh files: an OBJ with a nan, inf or garbage number names file and line", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  const std::string nan = dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(error_of([&] { read_mesh_file(nan); }) == nan + ":2: \"nan\" is not a finite number");
  const std::string inf = dir.write("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 inf\nf 1//1 2//1 3//1\n");
  CHECK(error_of([&] { read_mesh_file(inf); }) == inf + ":4: \"inf\" is not a finite number");
  const std::string junk = dir.write("junk.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 x\nf 1 2 3\n");
  CHECK(error_of([&] { read_mesh_file(junk); }) == junk + ":4: \"x\" is not a finite number");
  // Issue 23: a number past a float's range was read as infinity and the triangle dropped.
  const std::string big = dir.write("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 1e39\nf 1 2 3\n");
  CHECK(error_of([&] { read_mesh_file(big); }) == big + ":3: 1e39 is too large for a float (the largest is about 3.4e38)");
  const std::string none = dir.write("none.obj", "v 0 0 0\n");
  CHECK_THAT(error_of([&] { read_mesh_file(none); }), Contains("has no faces"));
  // Through a scene, the error keeps the file and line and adds the JSON pointer.
  const std::string scene = dir.write("scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "diffuse"}}, "objects": [{"type": "mesh", "file": "nan.obj", "material": "m"}]})");
  const std::string msg = error_of([&] { load_scene(scene); });
  CHECK_THAT(msg, Contains("/objects/0/file") && Contains("nan.obj:2: \"nan\" is not a finite number"));
}

TEST_CASE("mesh files: an OBJ face naming a vt or vn the file lacks is an error", "[mesh]" TIER_UNIT) {
  // Issue 23: these were ignored silently (the triangle lost its UVs or normals).
  test::TempDir dir;
  const std::string vt = dir.write("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nf 1/1 2/2 3/5\n");
  CHECK(error_of([&] { read_mesh_file(vt); }) ==
        "OBJ file " + vt + ": face 1 names texture coordinate (vt) 5, but the file has 2");
  const std::string vn = dir.write("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\no part\nf 1//1 2//1 3//1\nf 1//1 3//1 2//9\n");
  CHECK(error_of([&] { read_mesh_file(vn); }) == "OBJ file " + vn + ": face 2 of \"part\" names normal (vn) 9, but the file has 1");
  // In range they are read (and a corner without them is fine).
  const std::string ok = dir.write("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\nf 1 2 3\n");
  CHECK(read_mesh_file(ok).tris.size() == 2);
}

TEST_CASE("mesh files: ASCII PLY with normals and UVs reads back exactly", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  const Quad q;
  std::string text = ply_header("ascii", 4, 2);
  text += "0 0 0 0 0 1 0 0\n2 0 0 0 0.5 0.75 1 0\n2 1 0.5 0.25 0 1 1 0.75\n0 1 0.5 -0.5 0.125 1 0.125 0.25\n";
  text += "3 0 1 2\n3 0 2 3\n";
  const MeshData m = read_mesh_file(dir.write("quad.ply", text));
  check_quad(m, q, true, true, false);  // PLY's UVs as they are
  CHECK(m.verts.size() >= 4);

  // A quad face is triangulated; a PLY without normals and UVs has no attributes.
  std::string poly = ply_header("ascii", 4, 1, false) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  const MeshData p = read_mesh_file(dir.write("poly.ply", poly));
  CHECK(p.tris.size() == 2);
  CHECK(p.attributes.empty());
}

TEST_CASE("mesh files: binary little-endian PLY reads back exactly", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  const Quad q;
  const MeshData m = read_mesh_file(dir.write("quad.ply", binary_ply(q)));
  check_quad(m, q, true, true, false);
}

TEST_CASE("mesh files: a truncated binary PLY is an error", "[mesh]" TIER_PROCESS) {
  // Run through the executable: a reader that crashes on the file fails this test instead of
  // taking the test runner down with it.
  test::TempDir dir;
  const Quad q;
  const std::string whole = binary_ply(q);
  const size_t header = ply_header("binary_little_endian", 4, 2).size();
  REQUIRE(whole.size() == header + 4 * 32 + 2 * 13);
  // Cut inside the last face, inside the first face, inside the vertices, and all the data.
  for (size_t keep : {whole.size() - 5, header + 4 * 32 + 1, header + 4 * 32 - 7, header}) {
    INFO("kept " << keep - header << " of " << whole.size() - header << " bytes of data");
    const std::string name = "cut" + std::to_string(keep) + ".ply";
    dir.write(name, whole.substr(0, keep));
    dir.write("scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "render": {"width": 4, "height": 4, "spp": 1},
      "materials": {"m": {"type": "diffuse"}}, "objects": [{"type": "mesh", "file": ")" + name + R"(", "material": "m"}]})");
    const test::RunResult r = test::run_caustica("render scene.json -o out.png --quiet", dir);
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, StartsWith("error: scene.json: /objects/0/file: ") && Contains(name));
  }
}

TEST_CASE("mesh files: a PLY with a non-finite vertex is an error", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  Quad q;
  q.pos[1].y = std::numeric_limits<float>::quiet_NaN();
  const std::string bin = dir.write("nan.ply", binary_ply(q));
  CHECK_THAT(error_of([&] { read_mesh_file(bin); }), StartsWith(bin + ": vertex ") && Contains(" is not finite"));
  q.pos[1].y = 0.0f;
  q.pos[3].z = std::numeric_limits<float>::infinity();
  const std::string inf = dir.write("inf.ply", binary_ply(q));
  CHECK_THAT(error_of([&] { read_mesh_file(inf); }), StartsWith(inf + ": vertex ") && Contains(" is not finite"));
  std::string text = ply_header("ascii", 3, 1, false) + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n";
  const std::string ascii = dir.write("nan_ascii.ply", text);
  CHECK_THAT(error_of([&] { read_mesh_file(ascii); }), Contains(ascii));
}

TEST_CASE("mesh files: Mitsuba serialized shapes read back exactly and shape_index picks one", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  const Quad q;
  const SerializedShape quad = quad_shape(q), tri = triangle_shape();
  SECTION("one shape, without the table") {
    const std::string path = dir.write("one.serialized", serialized_shape(quad));
    const MeshData m = read_mesh_file(path);
    check_indexed_quad(m, q);
    check_quad(m, q, true, true, false);
  }
  SECTION("two shapes: index 0 and 1, out of range, negative") {
    const std::string path = dir.write("two.serialized", serialized_file({quad, tri}));
    const MeshData first = read_mesh_file(path, 0);
    check_quad(first, q, true, true, false);
    const MeshData second = read_mesh_file(path, 1);
    REQUIRE(second.verts.size() == 3);
    CHECK(second.verts[0] == Vec3(5, 0, 0));
    CHECK(second.verts[1] == Vec3(6, 0, 0));
    CHECK(second.verts[2] == Vec3(5, 3, -1));
    REQUIRE(second.tris.size() == 1);
    CHECK(second.tris[0] == glm::ivec3(0, 2, 1));
    CHECK(second.attributes.empty());  // neither normals nor UVs
    CHECK(error_of([&] { read_mesh_file(path, 2); }) == path + ": shape_index 2 is out of range (the file holds 2 shapes)");
    CHECK(error_of([&] { read_mesh_file(path, -1); }) == path + ": shape_index must not be negative");
    // shape_index is for .serialized only.
    const std::string obj = dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK_THAT(error_of([&] { read_mesh_file(obj, 1); }), Contains("shape_index applies to .serialized files only"));
  }
  SECTION("shape_index through a JSON scene and a Mitsuba scene") {
    dir.write("two.serialized", serialized_file({quad, tri}));
    const std::string json_scene = dir.write("scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "diffuse"}},
      "objects": [{"type": "mesh", "file": "two.serialized", "shape_index": 1, "material": "m"}]})");
    LoadedScene a = load_scene(json_scene);
    CHECK(a.triangle_count == 1);
    REQUIRE(a.scene->objects.size() == 1);
    CHECK(a.scene->objects[0].area == Approx(0.5f * std::sqrt(10.0f)));  // 0.5 |(1, 0, 0) x (0, 3, -1)|
    const std::string xml_scene = dir.write("scene.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0"/></transform></sensor>
  <shape type="serialized"><string name="filename" value="two.serialized"/><integer name="shape_index" value="1"/></shape>
  <shape type="serialized"><string name="filename" value="two.serialized"/></shape>
</scene>)");
    LoadedScene b = load_scene(xml_scene);
    CHECK(b.triangle_count == 3);
    REQUIRE(b.scene->objects.size() == 2);
    CHECK(b.scene->objects[0].area == Approx(0.5f * std::sqrt(10.0f)));
    // The quad: |(2,0,0) x (2,1,0.5)| / 2 + |(2,1,0.5) x (0,1,0.5)| / 2 = 2 * sqrt(1.25) / 2 * 2.
    CHECK(b.scene->objects[1].area == Approx(2.0f * std::sqrt(1.25f)));
    const std::string bad = dir.write("bad.xml", R"(<scene version="3.0.0">
  <shape type="serialized"><string name="filename" value="two.serialized"/><integer name="shape_index" value="5"/></shape>
</scene>)");
    const std::string msg = error_of([&] { load_scene(bad); });
    CHECK_THAT(msg, StartsWith(bad + ":2:"));
    CHECK_THAT(msg, Contains("shape_index 5 is out of range (the file holds 2 shapes)"));
  }
}

TEST_CASE("mesh files: a serialized shape's vertex colours are the mesh attribute vertex_color", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  const Quad q;
  SerializedShape quad = quad_shape(q);
  quad.colours = {0.5f, 0.25f, 0.125f, 1, 0, 0, 0, 1, 0, 2, 3, 4};
  const MeshData m = read_mesh_file(dir.write("c.serialized", serialized_shape(quad)));
  check_quad(m, q, true, true, false);  // the colours, between the UVs and the indices, are skipped right
  REQUIRE(m.extra.list.size() == 1);
  const MeshAttribute& a = m.extra.list[0];
  CHECK(a.name == "vertex_color");
  CHECK(a.channels == 3);
  CHECK_FALSE(a.per_face);
  REQUIRE(a.values.size() == 6);
  for (size_t t = 0; t < 2; ++t) {
    for (int k = 0; k < 3; ++k) {
      const size_t v = size_t(q.tris[t][k]);
      CHECK(a.values[3 * t + size_t(k)] == Color(quad.colours[3 * v], quad.colours[3 * v + 1], quad.colours[3 * v + 2]));
    }
  }
  quad.colours[4] = std::numeric_limits<float>::quiet_NaN();
  const std::string bad = dir.write("nan.serialized", serialized_shape(quad));
  CHECK(error_of([&] { read_mesh_file(bad); }) == bad + ": the colour of vertex 1 is not finite");
}

TEST_CASE("mesh files: a serialized shape is inflated only as far as its counts declare and memory allows", "[mesh]" TIER_PROCESS) {
  // Issue 23: a 1.2 MB file inflating to 1.2 GB reached 2.2 GB before its error.
  test::TempDir dir;
  // Counts of 2^28 vertices (3 GiB of positions) over 80 MiB of zeros: inflated past 64 MiB,
  // the rest is checked against the memory limit first.
  SerializedShape s;
  std::string raw = serialized_raw(s, uint64_t(1) << 28, 1);
  raw.append(size_t(80) << 20, '\0');
  dir.write("bomb.serialized", serialized_blob(raw));
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "diffuse"}}, "objects": [{"type": "mesh", "file": "bomb.serialized", "material": "m"}]})");
  if (test::kAddressSpaceLimits) {
    const auto r = test::run_caustica("render scene.json -o out.png", dir, test::address_space_limit(2 << 20));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("bomb.serialized (268435456 vertices, 1 triangles) needs about ") &&
                          Contains("GiB of memory; ") && Contains(" leaves "));
  }
  // Short of the counts and under 64 MiB, it is "truncated", whatever the memory.
  raw = serialized_raw(s, uint64_t(1) << 28, 1);
  raw.append(size_t(1) << 20, '\0');
  const std::string lying = dir.write("lying.serialized", serialized_blob(raw));
  CHECK(error_of([&] { read_mesh_file(lying); }) == lying + ": truncated while reading the vertex positions");
}

TEST_CASE("mesh files: a truncated or corrupt serialized file is an error", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  const Quad q;
  const std::string whole = serialized_shape(quad_shape(q));
  // The zlib stream cut short.
  const std::string cut = dir.write("cut.serialized", whole.substr(0, whole.size() / 2));
  CHECK(error_of([&] { read_mesh_file(cut); }) == cut + ": the compressed mesh data at byte 4 is truncated");
  // Complete zlib data holding fewer numbers than the counts say.
  SerializedShape short_shape = quad_shape(q);
  const std::string raw = serialized_raw(short_shape, 4, 2);
  const std::string short_pos = dir.write("short.serialized", serialized_blob(raw.substr(0, 4 + 5 + 16 + 3 * 4 * 3)));
  CHECK(error_of([&] { read_mesh_file(short_pos); }) == short_pos + ": truncated while reading the vertex positions");
  const std::string short_idx = dir.write("short_idx.serialized", serialized_blob(raw.substr(0, raw.size() - 4)));
  CHECK(error_of([&] { read_mesh_file(short_idx); }) == short_idx + ": truncated while reading the triangle indices");
  // An index beyond the vertices.
  SerializedShape wrong = triangle_shape();
  wrong.indices = {0, 1, 3};
  const std::string oob = dir.write("oob.serialized", serialized_shape(wrong));
  CHECK(error_of([&] { read_mesh_file(oob); }) == oob + ": triangle 0 has a vertex index out of range");
  // Not a serialized file at all, and a wrong version.
  const std::string magic = dir.write("magic.serialized", "PLY not really");
  CHECK_THAT(error_of([&] { read_mesh_file(magic); }), StartsWith(magic + ": not a Mitsuba .serialized mesh"));
  std::string v9 = whole;
  v9[2] = 9;
  const std::string version = dir.write("v9.serialized", v9);
  CHECK(error_of([&] { read_mesh_file(version); }) == version + ": unsupported .serialized version 9 (known: 3, 4)");
  // A non-finite vertex.
  SerializedShape nan = triangle_shape();
  nan.pos[4] = std::numeric_limits<float>::quiet_NaN();
  const std::string nan_path = dir.write("nan.serialized", serialized_shape(nan));
  CHECK(error_of([&] { read_mesh_file(nan_path); }) == nan_path + ": vertex 1 is not finite");
  // In memory, the same reader.
  CHECK(parse_serialized(whole, "mem", 0).tris.size() == 2);
  CHECK(error_of([&] { parse_serialized(whole.substr(0, 3), "mem", 0); }) == "mem: not a Mitsuba .serialized mesh (the file does not start with 0x041C)");
}

TEST_CASE("mesh files: an OBJ's mtl gives a JSON scene its materials and an area light", "[mesh]" TIER_UNIT) {
  test::TempDir dir;
  dir.write("lit.mtl", "newmtl white\nKd 0.5 0.25 0.125\n\nnewmtl lamp\nKd 0 0 0\nKe 2 3 4\n");
  dir.write("lit.obj", R"(mtllib lit.mtl
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
v 0 0 1
v 1 0 1
v 0 1 1
usemtl white
f 1 2 3
f 1 3 4
usemtl lamp
f 5 6 7
)");
  const std::string scene = dir.write("scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "render": {"width": 8, "height": 8, "spp": 1},
    "materials": {},
    "objects": [{"type": "mesh", "file": "lit.obj"}]})");
  LoadedScene loaded = load_scene(scene);
  const Scene& s = *loaded.scene;
  CHECK(loaded.triangle_count == 3);
  CHECK(loaded.warnings.empty());
  REQUIRE(s.material_names.size() == 2);
  auto material = [&](const std::string& name) -> const Bsdf& {
    for (size_t i = 0; i < s.material_names.size(); ++i) {
      if (s.material_names[i] == name) return *s.materials[i];
    }
    FAIL("no material " << name);
    return *s.materials[0];
  };
  const Bsdf& white = material("lit.obj#white");
  const Bsdf& lamp = material("lit.obj#lamp");
  CHECK(white.albedo() == Color(0.5f, 0.25f, 0.125f));
  CHECK(lamp.albedo() == Color(0.0f));
  // One object per material, the lamp one area light.
  REQUIRE(s.objects.size() == 2);
  double white_area = 0, lamp_area = 0;
  for (const ObjectInfo& o : s.objects) (s.material_names[o.material] == "lit.obj#lamp" ? lamp_area : white_area) += o.area;
  CHECK(white_area == Approx(4.0));
  CHECK(lamp_area == Approx(0.5));
  REQUIRE(s.lights.size() == 1);
  const auto* area = dynamic_cast<const AreaLight*>(s.lights[0].get());
  REQUIRE(area != nullptr);
  CHECK(area->surface_radiance() == Color(2, 3, 4));
  CHECK(area->area() == Approx(0.5f));
  // A "material" on the object overrides the file's.
  const std::string given = dir.write("given.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "diffuse", "reflectance": 0.3}},
    "objects": [{"type": "mesh", "file": "lit.obj", "material": "m"}]})");
  LoadedScene g = load_scene(given);
  CHECK(g.scene->materials.size() == 1);
  CHECK(g.scene->lights.empty());
  CHECK(g.scene->objects.size() == 1);
}

TEST_CASE("mesh files: big-endian PLY with a quad face and an extra element reads as a fan of two triangles", "[mesh]" TIER_UNIT) {
  std::string ply =
      "ply\nformat binary_big_endian 1.0\ncomment made by hand\nelement vertex 4\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty uchar flags\nproperty list uchar uint vertex_index\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  auto be = [&](const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    for (size_t i = 0; i < n; ++i) ply += c[n - 1 - i];
  };
  const double pos[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, -1.5}};
  for (const auto& v : pos)
    for (double x : v) be(&x, 8);
  ply += char(7);  // flags
  ply += char(4);
  for (uint32_t i : {0u, 1u, 2u, 3u}) be(&i, 4);
  for (int32_t i : {0, 1}) be(&i, 4);
  const MeshData m = parse_ply(ply, "be.ply");
  REQUIRE(m.verts.size() == 4);
  CHECK(m.verts[2] == Vec3(2, 3, 0));
  CHECK(m.verts[3] == Vec3(0, 3, -1.5f));
  REQUIRE(m.tris.size() == 2);
  CHECK(m.tris[0] == glm::ivec3(0, 1, 2));
  CHECK(m.tris[1] == glm::ivec3(0, 2, 3));
  CHECK(m.attributes.empty());
  // The edge element is walked: cutting it short is an error.
  CHECK_THAT(error_of([&] { parse_ply(ply.substr(0, ply.size() - 2), "be.ply"); }), Contains("truncated"));
}

TEST_CASE("mesh files: PLY errors name the line or the element", "[mesh]" TIER_UNIT) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  CHECK(error_of([&] { parse_ply(head + "0 0 0\n1 0 0\n", "a.ply"); }) ==
        "a.ply:12: the file ends before vertex 2 (truncated)");
  CHECK(error_of([&] { parse_ply(head + "0 0 0\n1 0 0\n0 1 0 5\n3 0 1 2\n", "a.ply"); }) ==
        "a.ply:12: vertex 2 has more values than its properties");
  CHECK(error_of([&] { parse_ply(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "a.ply"); }) ==
        "a.ply:13: face 0 has a vertex index out of range");
  CHECK(error_of([&] { parse_ply(head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "a.ply"); }) ==
        "a.ply:13: face 0 has 2 vertices (3 or more needed)");
  // A binary file claiming 2^31 vertices is refused before anything is allocated.
  const std::string huge = "ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty float x\n"
                           "property float y\nproperty float z\nend_header\n" + std::string(24, '\0');
  CHECK_THAT(error_of([&] { parse_ply(huge, "h.ply"); }), Contains("too short for its 2147483648 vertex elements"));
  CHECK_THAT(error_of([&] { parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", "t.ply"); }),
             Contains("unknown type \"quad\""));
  CHECK_THAT(error_of([&] { parse_ply("solid cube\n", "s.ply"); }), Contains("not a PLY file"));
}

TEST_CASE("mesh files: counts larger than the data are refused before anything is allocated", "[mesh]" TIER_UNIT) {
  // A .serialized stream of a few bytes declaring 2^31 vertices.
  SerializedShape tiny;
  tiny.name = "huge";
  const std::string blob = serialized_blob(serialized_raw(tiny, uint64_t(1) << 31, 1));
  CHECK(error_of([&] { parse_serialized(blob, "h.serialized", 0); }) == "h.serialized: truncated while reading the vertex positions");
  SerializedShape one;
  one.pos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  one.name = "t";
  CHECK(error_of([&] { parse_serialized(serialized_blob(serialized_raw(one, 3, uint64_t(1) << 31)), "t.serialized", 0); }) ==
        "t.serialized: truncated while reading the triangle indices");
  // An ASCII PLY declaring 2^31 vertices and holding one.
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 2147483648\nproperty float x\nproperty float y\n"
                          "property float z\nend_header\n0 0 0\n";
  CHECK(error_of([&] { parse_ply(ply, "a.ply"); }) == "a.ply:9: the file ends before vertex 1 (truncated)");
  // A list count too large for any integer.
  const std::string list = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uint int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                           "99999999999999999999 0 1 2\n";
  CHECK_THAT(error_of([&] { parse_ply(list, "l.ply"); }), Contains("items (0 to 10^6 allowed)"));
}

TEST_CASE("mesh files: smooth normals average the faces around a vertex by area", "[mesh]" TIER_UNIT) {
  // Two triangles folded at 90 degrees along the x axis: the shared vertices get the normalised
  // sum of the two face normals weighted by twice their areas.
  MeshData m;
  m.verts = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 2)};
  m.tris = {glm::ivec3(0, 1, 2), glm::ivec3(0, 3, 1)};
  add_smooth_normals(m);
  REQUIRE(m.attributes.size() == 2);
  // Face 0: cross((1,0,0),(0,1,0)) = (0,0,1), area 0.5; face 1: cross((0,0,2),(1,0,0)) = (0,2,0), area 1.
  const Vec3 shared = glm::normalize(Vec3(0, 2, 1));
  CHECK(glm::length(m.attributes[0].n[0] - shared) < 1e-6f);
  CHECK(glm::length(m.attributes[0].n[1] - shared) < 1e-6f);
  CHECK(glm::length(m.attributes[0].n[2] - Vec3(0, 0, 1)) < 1e-6f);
  CHECK(glm::length(m.attributes[1].n[1] - Vec3(0, 1, 0)) < 1e-6f);
  CHECK(m.attributes[0].has_normals);
  CHECK_FALSE(m.attributes[0].has_uvs);
}

TEST_CASE("mesh files: max_smooth_angle keeps creases sharper than the angle, smooths the rest", "[mesh]" TIER_UNIT) {
  // Issue 24 (Mitsuba 0.6's maxSmoothAngle): a floor triangle (normal +y) and a wall triangle
  // (normal +z) of equal area sharing the edge from vertex 0 to 1, at 90 degrees; the file's own
  // normals (all +x) are dropped.
  test::TempDir dir;
  const std::string path = dir.write("crease.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 0 1 0\nvn 1 0 0\n"
                                                  "f 1//1 2//1 3//1\nf 1//1 2//1 4//1\n");
  MeshData sharp = read_mesh_file(path);
  REQUIRE(sharp.tris.size() == 2);
  rebuild_normals_with_creases(sharp, 60.0);
  for (int k = 0; k < 3; ++k) {
    CHECK(glm::length(sharp.attributes[0].n[k] - Vec3(0, 1, 0)) < 1e-6f);
    CHECK(glm::length(sharp.attributes[1].n[k] - Vec3(0, 0, 1)) < 1e-6f);
  }
  MeshData smooth = read_mesh_file(path);
  rebuild_normals_with_creases(smooth, 100.0);
  const Vec3 mean = glm::normalize(Vec3(0, 1, 1));
  // The shared vertices (0 and 1) average both faces; the others see only their own.
  CHECK(glm::length(smooth.attributes[0].n[0] - mean) < 1e-6f);
  CHECK(glm::length(smooth.attributes[0].n[1] - mean) < 1e-6f);
  CHECK(glm::length(smooth.attributes[0].n[2] - Vec3(0, 1, 0)) < 1e-6f);
  CHECK(glm::length(smooth.attributes[1].n[2] - Vec3(0, 0, 1)) < 1e-6f);
  // Through a scene and from a 0.6 Mitsuba scene; with face_normals it is an error.
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {"m": {"type": "diffuse"}},
    "objects": [{"type": "mesh", "file": "crease.obj", "material": "m", "max_smooth_angle": 60}]})");
  CHECK(load_scene(dir.file("scene.json")).scene->attributes.size() == 2);
  dir.write("both.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {"m": {"type": "diffuse"}},
    "objects": [{"type": "mesh", "file": "crease.obj", "material": "m", "max_smooth_angle": 60, "face_normals": true}]})");
  CHECK_THAT(error_of([&] { load_scene(dir.file("both.json")); }),
             Contains("/objects/0/max_smooth_angle: max_smooth_angle and face_normals exclude each other"));
  const std::string xml = dir.write("old.xml", R"(<scene version="0.6.0">
  <shape type="obj"><string name="filename" value="crease.obj"/><float name="maxSmoothAngle" value="30"/></shape>
</scene>)");
  const nlohmann::json d = read_mitsuba(test::read_text(xml), xml, dir.path().string(), {}).doc;
  CHECK(d["objects"][0]["max_smooth_angle"] == 30.0);
  CHECK_FALSE(d["objects"][0].contains("smooth_normals"));
}
