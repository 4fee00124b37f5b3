// Scene assembly and ray queries.
#include "core/scene.h"

namespace caustica {

void Scene::build(std::vector<Primitive> prims) {
  bvh_.build(std::move(prims));
  bounds_ = bvh_.bounds();
  for (const auto& light : lights) bounds_.extend(light->bounds());
  // Lights at infinity need the scene's bounding sphere before their power is known.
  const Vec3 centre = bounds_.centre();
  const float radius = std::max(0.5f * glm::length(bounds_.extent()), 1e-3f);
  environment_.clear();
  for (size_t i = 0; i < lights.size(); ++i) {
    if (!lights[i]->is_infinite()) continue;
    lights[i]->set_scene_sphere(centre, radius);
    if (!lights[i]->is_delta()) environment_.push_back(i);
  }
  std::vector<float> powers;
  for (const auto& light : lights) powers.push_back(average(light->power()));
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

Color Scene::escaped(const Vec3& dir) const {
  Color L(0.0f);
  for (size_t i : environment_) L += lights[i]->escaped(dir);
  return L;
}

float Scene::pdf_escaped(const Vec3& dir) const {
  float pdf = 0.0f;
  for (size_t i : environment_) pdf += light_pmf(i) * lights[i]->pdf_escaped(dir);
  return pdf;
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
