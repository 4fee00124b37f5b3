// Self-intersection: rays leaving a surface, even at grazing angles, never hit it again.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "io/scene_loader.h"
#include "core/rng.h"
#include "core/sampling.h"

using namespace caustica;

TEST_CASE("offset: grazing rays leaving a surface do not hit it again", "[core][offset]" TIER_UNIT) {
  // A tilted quad and a sphere, at small and at Cornell-box scale.
  for (float scale : {1.0f, 550.0f}) {
    const std::string s = std::to_string(scale);
    const std::string text = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "diffuse"}},
      "objects": [{"type": "quad", "origin": [)" + s + R"(, 0, 0], "edge1": [)" + s + R"(, 0.3, 0], "edge2": [0, 0.2, )" + s + R"(], "material": "m"},
                  {"type": "sphere", "center": [0, 0, 0], "radius": )" + std::to_string(0.5f * scale) + R"(, "material": "m"}]})";
    LoadedScene loaded = parse_scene(text, "offset.json", ".");
    const Scene& scene = *loaded.scene;
    const auto& prims = scene.accel().primitives();
    Rng rng(17);
    int self_hits = 0, tries = 0;
    for (const Primitive& prim : prims) {
      for (int i = 0; i < 2000; ++i) {
        Vec3 n;
        const Vec3 p = prim.sample_point(Vec2(rng.next_float(), rng.next_float()), &n);
        // Elevation between 1e-4 and 1e-2 radians above the surface, on either side.
        const float elevation = std::pow(10.0f, -4.0f + 2.0f * rng.next_float());
        const Frame f(rng.next_float() < 0.5f ? n : -n);
        const float phi = 2 * kPi * rng.next_float();
        const Vec3 dir = f.to_world(Vec3(std::cos(elevation) * std::cos(phi), std::cos(elevation) * std::sin(phi),
                                         std::sin(elevation)));
        const Ray ray = spawn_ray(p, n, dir);
        SurfaceHit hit;
        ++tries;
        const bool hit_something = scene.intersect(ray, hit);
        const bool same_surface = hit_something && glm::length(hit.n - prim.normal_at(hit.p)) < 1e-3f;
        if (prim.kind == ShapeKind::Triangle) {
          // A plane can never be hit again by a ray leaving it.
          self_hits += same_surface && std::abs(glm::dot(hit.p - prim.p0, n)) < 1e-3f * scale;
        } else if (glm::dot(dir, n) > 0) {
          self_hits += same_surface;  // leaving a sphere outwards: it is behind the ray
        } else {
          // Inwards: the far side of the chord, 2 r sin(elevation) away, not the start point.
          const float chord = 2.0f * prim.radius() * std::sin(elevation);
          self_hits += !same_surface || hit.t < 0.5f * chord;
        }
      }
    }
    INFO("scale " << scale << ": " << self_hits << " self-intersections of " << tries);
    CHECK(self_hits == 0);
  }
}
