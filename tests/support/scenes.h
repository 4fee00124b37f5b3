// Small analytic scenes shared by the integrator tests.
#pragma once
#include <string>

namespace caustica::test {

// Camera inside a closed sphere (normals flipped inward) with albedo `albedo` and emission
// `emission`: every pixel's radiance is emission / (1 - albedo).
inline std::string furnace_scene(double albedo, double emission, const std::string& integrator_json,
                                 int spp = 16, int size = 32) {
  return R"({
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0], "fov": 90},
    "render": {"width": )" + std::to_string(size) + R"(, "height": )" + std::to_string(size) +
         R"(, "spp": )" + std::to_string(spp) + R"(, "seed": 7, "max_depth": 1000},
    "integrator": )" + integrator_json + R"(,
    "materials": {"shell": {"type": "diffuse", "albedo": [)" + std::to_string(albedo) + "," +
         std::to_string(albedo) + "," + std::to_string(albedo) + R"(], "emission": [)" + std::to_string(emission) +
         "," + std::to_string(emission) + "," + std::to_string(emission) + R"(]}},
    "objects": [{"type": "sphere", "center": [0.3, -0.2, 0.1], "radius": 2, "material": "shell", "flip_normal": true}]
  })";
}

// A diffuse floor (100 x 100 at y = 0) seen from straight above through a narrow camera, lit
// by the given light block.
inline std::string floor_scene(const std::string& light, double albedo = 0.5) {
  return R"({
    "camera": {"position": [0, 4, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 2},
    "materials": {"floor": {"type": "diffuse", "reflectance": )" + std::to_string(albedo) + R"(}},
    "objects": [{"type": "quad", "origin": [-50, 0, -50], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "floor"}],
    "lights": [)" + light + "]}";
}

// The same floor under a square emitter of radiance 1 and half-side `half`, 1 unit above the
// floor's centre and facing it, seen from straight above at height camera_y (below the emitter).
inline std::string floor_under_square_light(double half, double camera_y) {
  const std::string a = std::to_string(half), e = std::to_string(2 * half);
  return R"({
    "camera": {"position": [0, )" + std::to_string(camera_y) + R"(, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 2},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.5},
                  "light": {"type": "diffuse", "reflectance": 0, "emission": [1, 1, 1]}},
    "objects": [{"type": "quad", "origin": [-50, 0, -50], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "floor"},
                {"type": "quad", "origin": [-)" + a + ", 1, -" + a + R"(], "edge1": [)" + e + R"(, 0, 0], "edge2": [0, 0, )" + e +
         R"(], "material": "light"}]})";
}

}  // namespace caustica::test
