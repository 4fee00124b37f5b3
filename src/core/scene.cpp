// Scene assembly and ray queries.
#include "core/scene.h"
#include <cstring>
#include "core/rng.h"

namespace caustica {
void Scene::build(std::vector<Primitive> prims) {
  has_masks_ = false;
  for (const auto& m : materials) has_masks_ = has_masks_ || m->has_mask();
  accel_ = make_accelerator(render.accel, std::move(prims));
  bounds_ = accel_->bounds();
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
  light_sampler_ = LightSampler(lights, render.light_sampler);
}

void Scene::set_accel(AccelKind kind) {
  if (kind == render.accel) return;
  render.accel = kind;
  accel_ = make_accelerator(kind, accel_->primitives());
}

bool Scene::intersect(const Ray& ray_in, SurfaceHit& hit) const {
  if (!has_masks_) return intersect_opaque(ray_in, hit);
  // Masked surfaces let a ray through with probability 1 - opacity, decided by a hash of the
  // ray and the hit (the same for any thread count); the ray then goes on beyond the hit.
  Ray ray = ray_in;
  float travelled = 0.0f;
  for (int pass = 0; pass < 256; ++pass) {
    if (!intersect_opaque(ray, hit)) return false;
    const float alpha = hit.material->opacity(hit.sp);
    // (A surface bounding media stops every ray: the medium changes there.)
    if (alpha >= 1.0f || hit.media) {
      hit.t += travelled;
      return true;
    }
    uint32_t bits[7];
    std::memcpy(bits, &ray.origin, sizeof(float) * 3);
    std::memcpy(bits + 3, &ray.dir, sizeof(float) * 3);
    std::memcpy(bits + 6, &hit.t, sizeof(float));
    const uint64_t h = hash_seed((uint64_t(bits[0]) << 32) | bits[1], (uint64_t(bits[2]) << 32) | bits[3],
                                 (uint64_t(bits[4]) << 32 | bits[5]) ^ (uint64_t(bits[6]) << 16));
    const float u = float(h >> 40) * 0x1.0p-24f;
    if (u < alpha) {
      hit.t += travelled;
      return true;
    }
    const Vec3 origin = offset_origin(hit.p, hit.n, ray.dir);
    const float step = glm::length(origin - ray.origin);
    travelled += step;
    ray = Ray{origin, ray.dir, ray.tmax - step};
    if (!(ray.tmax > 0.0f)) return false;
  }
  return false;
}

bool Scene::occluded(const Ray& ray) const {
  if (!has_masks_) return accel_->occluded(ray);
  SurfaceHit hit;
  return intersect(ray, hit);
}

Color Scene::transmittance(const Ray& ray, int32_t medium, Sampler& sampler) const {
  if (!has_media()) return occluded(ray) ? Color(0.0f) : Color(1.0f);
  Color tr;
  SurfaceHit hit;
  return walk(ray, medium, sampler, tr, hit) ? Color(0.0f) : tr;
}

bool Scene::walk(const Ray& ray_in, int32_t medium, Sampler& sampler, Color& tr, SurfaceHit& hit) const {
  Ray ray = ray_in;
  tr = Color(1.0f);
  for (int crossing = 0; crossing < 256; ++crossing) {
    const bool found = intersect(ray, hit);
    if (medium >= 0) tr *= media[size_t(medium)]->transmittance(ray, found ? hit.t : ray.tmax, sampler);
    if (!found) return false;
    // (A null lobe, thindielectric's, lets the ray through with its weight, as in Mitsuba's
    // volpath; its surface may or may not bound a medium.)
    if (!passes_straight(hit)) return true;
    if (!is_medium_boundary(hit)) tr *= hit.material->null_transmission(hit.frame.to_local(-ray.dir), hit.sp);
    if (is_black(tr)) break;
    if (hit.media) medium = hit.media->entered(ray.dir, hit.n);
    ray = continued(ray, hit);
    if (!(ray.tmax > 0.0f)) return false;
  }
  tr = Color(0.0f);
  return false;
}

int32_t Scene::medium_at(const Vec3& p, const Vec3& dir) const {
  if (!has_media()) return -1;
  Ray ray{p, dir, kInfinity};
  for (int crossing = 0; crossing < 256; ++crossing) {
    SurfaceHit hit;
    if (!intersect(ray, hit)) break;
    // The ray leaves the side it started on: the interior when it crosses outwards.
    if (hit.media) return glm::dot(dir, hit.n) < 0.0f ? hit.media->exterior : hit.media->interior;
    ray = Ray{offset_origin(hit.p, hit.n, dir), dir, kInfinity};
  }
  return outside_medium();
}

int32_t Scene::outside_medium() const {
  if (!has_media()) return -1;
  if (interfaces.empty()) return camera_medium;  // (a medium without bounds fills the scene)
  // From outside the scene's box towards its centre: the first boundary's outer side.
  const Vec3 c = bounds().centre(), dir = glm::normalize(Vec3(0.267f, 0.535f, 0.802f));
  Ray ray{c - dir * (glm::length(bounds().extent()) + 1.0f), dir, kInfinity};
  for (int crossing = 0; crossing < 256; ++crossing) {
    SurfaceHit hit;
    if (!intersect(ray, hit)) break;
    if (hit.media) return glm::dot(dir, hit.n) < 0.0f ? hit.media->exterior : hit.media->interior;
    ray = Ray{offset_origin(hit.p, hit.n, dir), dir, kInfinity};
  }
  return -1;
}

bool Scene::intersect_opaque(const Ray& ray, SurfaceHit& hit) const {
  Hit h;
  if (!accel_->intersect(ray, h)) return false;
  const Primitive& prim = accel_->primitives()[h.prim];
  hit.t = h.t;
  hit.p = ray.at(h.t);
  if (prim.kind == ShapeKind::Sphere) {
    // Project back onto the sphere: removes the error of the ray's parametric point.
    hit.p = prim.p0 + prim.radius() * glm::normalize(hit.p - prim.p0);
  }
  const bool curve = prim.kind == ShapeKind::LinearCurve || prim.kind == ShapeKind::BsplineCurve;
  const Primitive::AxisPoint axis_point = curve ? prim.curve_axis_point(hit.p) : Primitive::AxisPoint{};
  hit.n = curve ? prim.curve_normal(hit.p, axis_point) : prim.normal_at(hit.p);
  hit.material = materials[prim.material].get();
  hit.light = prim.light;
  hit.media = prim.media ? &interfaces[prim.media - 1u] : nullptr;
  Vec3 ns = hit.n;
  // dp/du orients anisotropic BSDFs, as Mitsuba's shading frames do; with dp/dv it bends
  // bump-mapped normals.
  Vec3 dpdu(0.0f), dpdv(0.0f), tangent(0.0f);
  hit.sp.uv = Vec2(0.0f);
  hit.sp.mesh = nullptr;
  hit.sp.tilted_by = nullptr;
  if (prim.kind == ShapeKind::Sphere) {
    // u = phi / 2 pi, v = theta / pi (sphere_uv).
    const Vec3 d = (hit.p - prim.p0) / prim.radius();
    hit.sp.uv = sphere_uv(d);
    const float r = prim.radius(), sin_theta = std::sqrt(d.x * d.x + d.y * d.y);
    tangent = Vec3(-d.y, d.x, 0.0f);
    dpdu = (2.0f * kPi * r) * tangent;
    if (sin_theta > 1e-6f) dpdv = (kPi * r) * Vec3(d.z * d.x / sin_theta, d.z * d.y / sin_theta, -sin_theta);
  } else if (curve) {
    // Mitsuba's parameterisation: u around the axis (from a frame about it), v along the
    // file's segments; dp/dv along the axis orients anisotropic BSDFs along the fibre.
    const Vec3 radial = hit.p - axis_point.centre;
    const Frame around(glm::normalize(axis_point.axis));
    const float u = std::atan2(glm::dot(radial, around.t), glm::dot(radial, around.s)) * (0.5f * kInvPi);
    const float segments = float(prim.curve_segments());
    hit.sp.uv = Vec2(u < 0.0f ? u + 1.0f : u, (axis_point.s + float(prim.curve_segment())) / segments);
    dpdv = axis_point.axis * segments;
    dpdu = (2.0f * kPi) * glm::cross(around.n, radial);
    tangent = dpdu;
  } else if (prim.kind == ShapeKind::SdfVoxel) {
    // No UVs (as in Mitsuba); the grid's shading normal (smooth or the interpolant's own).
    const Vec3 n = prim.sdf_grid()->shading_normal(hit.p, prim.sdf_voxel(), prim.flip ? -hit.n : hit.n);
    ns = prim.flip ? -n : n;
  } else if (prim.attributes != kNoAttributes) {
    const TriangleAttributes& a = attributes[prim.attributes];
    const Vec3 b = barycentrics(prim, hit.p);
    if (a.mesh) {
      hit.sp.mesh = a.mesh;
      hit.sp.triangle = a.triangle;
      hit.sp.bary = b;
    }
    if (a.has_uvs) {
      hit.sp.uv = b.x * a.uv[0] + b.y * a.uv[1] + b.z * a.uv[2];
      const Vec2 duv1 = a.uv[1] - a.uv[0], duv2 = a.uv[2] - a.uv[0];
      const float det = duv1.x * duv2.y - duv1.y * duv2.x;
      if (std::abs(det) > 1e-12f) {
        const Vec3 e1 = prim.p1 - prim.p0, e2 = prim.p2 - prim.p0;
        dpdu = tangent = (duv2.y * e1 - duv1.y * e2) / det;
        dpdv = (duv1.x * e2 - duv2.x * e1) / det;
      }
    }
    if (a.has_normals) {
      const Vec3 n = b.x * a.n[0] + b.y * a.n[1] + b.z * a.n[2];
      const float len = glm::length(n);
      if (len > 1e-8f && std::isfinite(len)) ns = (prim.flip ? -n : n) / len;
      if (glm::dot(ns, hit.n) < 0.0f) ns = -ns;  // the winding decides the side; the normals only bend it
    }
  }
  hit.frame = Frame(ns, tangent);
  hit.sp.dpdu = hit.frame.to_local(dpdu);
  hit.sp.dpdv = hit.frame.to_local(dpdv);
  return true;
}

Color Scene::escaped(const Vec3& dir) const {
  Color L(0.0f);
  for (size_t i : environment_) L += lights[i]->escaped(dir);
  return L;
}

float Scene::surface_area() const {
  float a = 0;
  for (const ObjectInfo& o : objects) a += o.area;
  return a;
}

const Light* Scene::sample_photon_light(float u, float& pmf) const {
  if (lights.empty()) return nullptr;
  return lights[light_sampler_.sample_by_power(u, pmf)].get();
}

const Light* Scene::sample_light_defensive(float u, float& pmf) const {
  pmf = 0.0f;
  if (lights.empty()) return nullptr;
  const size_t n = lights.size();
  constexpr float kBelowOne = 0x1.fffffep-1f;  // (u < 1: 2u and 2u - 1 must stay below 1)
  size_t i;
  if (u < 0.5f) {
    float by_power;
    i = light_sampler_.sample_by_power(std::min(2.0f * u, kBelowOne), by_power);
  } else {
    i = std::min(n - 1, size_t(std::min(2.0f * u - 1.0f, kBelowOne) * float(n)));
  }
  pmf = 0.5f * (light_sampler_.pmf_by_power(i) + 1.0f / float(n));
  return lights[i].get();
}

}  // namespace caustica
