// Scene assembly and ray queries.
#include "core/scene.h"

namespace caustica {

void Scene::build(std::vector<Primitive> prims) {
  bvh_.build(std::move(prims));
  bounds_ = bvh_.bounds();
  std::vector<float> powers;
  for (const auto& light : lights) {
    powers.push_back(average(light->power()));
    bounds_.extend(light->bounds());
  }
  light_distribution_ = Distribution1D(powers.data(), powers.size());
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit) const {
  Hit h;
  if (!bvh_.intersect(ray, h)) return false;
  const Primitive& prim = bvh_.primitives()[h.prim];
  hit.t = h.t;
  hit.p = ray.at(h.t);
  if (prim.kind == ShapeKind::Sphere) {
    // Project back onto the sphere: removes the error of the ray's parametric point.
    hit.p = prim.p0 + prim.radius() * glm::normalize(hit.p - prim.p0);
  }
  hit.n = prim.normal_at(hit.p);
  hit.material = materials[prim.material].get();
  hit.light = prim.light;
  hit.frame = Frame(hit.n);
  return true;
}

float Scene::surface_area() const {
  float a = 0;
  for (const ObjectInfo& o : objects) a += o.area;
  return a;
}

const Light* Scene::sample_light(float u, float& pmf) const {
  if (lights.empty()) return nullptr;
  return lights[light_distribution_.sample(u, &pmf)].get();
}

}  // namespace caustica
