// The scene: camera, materials, lights, geometry in a BVH and render settings.
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/bvh.h"
#include "core/camera.h"
#include "core/light_sampler.h"
#include "core/media/medium.h"
#include "core/lights/light.h"
#include "core/pixel_filter.h"
#include "core/sampler.h"
#include "core/bsdf/bsdf.h"
#include "core/textures/texture.h"

namespace caustica {

struct RenderSettings {
  int width = 512;
  int height = 512;
  int spp = 16;
  uint64_t seed = 0;
  int max_depth = 16;
  AccelKind accel = default_accel();  // the ray-casting backend
  LightSamplerKind light_sampler = LightSamplerKind::Tree;  // how shadow rays choose a light
  PixelFilter filter;                 // the pixel reconstruction filter (box by default)
};

struct SurfaceHit {
  Vec3 p;
  Vec3 n;  // geometric normal (front side = emitting / outside), unit length
  float t = kInfinity;
  const Bsdf* material = nullptr;
  int32_t light = -1;
  // The media on the surface's two sides, where it bounds any (else the ray's medium stays).
  const MediumInterface* media = nullptr;
  Frame frame;      // the shading frame: around the interpolated vertex normal, or n
  ShadingPoint sp;  // texture coordinates
  // A direction that the shading frame and the geometric normal put on different sides: the
  // light leaks that shading normals cause. Integrators drop such light and BSDF samples, as
  // Mitsuba's path tracers do with "strict normals" (Mitsuba 0.6's option; pbrt-v4 and
  // Mitsuba 3 evaluate in the shading frame alone and accept the leak).
  bool leaks(const Vec3& w) const { return glm::dot(w, n) * glm::dot(w, frame.n) <= 0.0f; }
};

// One scene object's bounding sphere and material (photon emission aims at specular ones).
struct ObjectInfo {
  Vec3 centre;
  float radius = 0;
  uint32_t material = 0;
  float area = 0;
};

class Scene {
 public:
  Camera camera;
  RenderSettings render;
  std::string source_file;

  std::vector<std::unique_ptr<Bsdf>> materials;
  std::vector<std::unique_ptr<Texture>> textures;  // read by the materials
  std::vector<TriangleAttributes> attributes;      // indexed by Primitive::attributes
  std::vector<std::unique_ptr<MeshAttributes>> mesh_attributes;  // pointed to by attributes
  std::vector<std::unique_ptr<SdfGrid>> sdf_grids;  // pointed to by their voxels' primitives
  // B-spline curves' control points, four for each segment, pointed to by the segments' primitives.
  std::vector<std::unique_ptr<std::vector<glm::vec4>>> curve_points;
  std::vector<std::string> material_names;
  std::vector<std::unique_ptr<Light>> lights;
  std::vector<ObjectInfo> objects;
  // Participating media, the pairs of them that surfaces separate (Primitive::media), and the
  // one the camera sits in (-1: none).
  std::vector<std::unique_ptr<Medium>> media;
  std::vector<MediumInterface> interfaces;
  int32_t camera_medium = -1;
  // Whether any medium is in use (one declared and named nowhere changes nothing).
  bool has_media() const { return camera_medium >= 0 || !interfaces.empty(); }

  // Builds the ray-casting structure (render.accel) over the primitives and the light sampler
  // (render.light_sampler).
  void build(std::vector<Primitive> prims);
  // Casts rays through another backend from now on (the same primitives).
  void set_accel(AccelKind kind);
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  // Shadow rays: any hit before ray.tmax, masked surfaces passed as intersect() passes them.
  bool occluded(const Ray& ray) const;
  // A shadow ray through media: the transmittance over [0, ray.tmax] from `medium` on, through
  // the surfaces that only bound media (null BSDF) and those with a null lobe (thindielectric,
  // at its null_transmission); zero at any other surface. Without media, 0 or 1 as occluded()
  // says (Mitsuba's path stops at a thindielectric, its volpath passes it).
  Color transmittance(const Ray& ray, int32_t medium, Sampler& sampler) const;
  // The walk transmittance() takes (in a scene with media): true at the first surface within
  // ray.tmax that does not let the ray straight through (hit; tr the transmittance to it);
  // false where the ray ends or leaves the scene first (tr to there), or nothing passes (tr 0).
  bool walk(const Ray& ray, int32_t medium, Sampler& sampler, Color& tr, SurfaceHit& hit) const;
  // The medium at point p (-1: none): the near side of the first surface bounding media that a
  // ray from p along dir meets; where none is met, outside_medium(). Light sources use it for
  // the medium their photons start in.
  int32_t medium_at(const Vec3& p, const Vec3& dir) const;
  // The medium outside every boundary: the outer side of the first one met from outside the
  // scene; the camera's where no surface bounds media (it then fills the scene).
  int32_t outside_medium() const;
  // A surface that bounds media and is not there for light (null BSDF): rays pass it.
  static bool is_medium_boundary(const SurfaceHit& hit) { return hit.media && hit.material->opacity(hit.sp) <= 0.0f; }
  // A surface a ray through media goes straight on past: one that only bounds media, or one
  // with a null lobe (thindielectric's, with its null_transmission).
  static bool passes_straight(const SurfaceHit& hit) {
    return is_medium_boundary(hit) || hit.material->has(kBsdfNull);
  }
  // The rest of `ray` past `hit`, on the far side, in the same direction (tmax what remains).
  static Ray continued(const Ray& ray, const SurfaceHit& hit) {
    const Vec3 origin = offset_origin(hit.p, hit.n, ray.dir);
    return Ray{origin, ray.dir, ray.tmax - glm::length(origin - ray.origin)};
  }
  // Takes ray on past a medium boundary (is_medium_boundary(hit)) into the medium beyond it.
  static void cross(const SurfaceHit& hit, Ray& ray, int32_t& medium) {
    medium = hit.media->entered(ray.dir, hit.n);
    ray = continued(ray, hit);
  }
  // Chooses a light for a shadow ray from p (shading normal n), by render.light_sampler;
  // null where none can reach p.
  const Light* sample_light(const Vec3& p, const Vec3& n, float u, float& pmf) const {
    const int i = light_sampler_.sample(p, n, u, pmf);
    return i >= 0 ? lights[size_t(i)].get() : nullptr;
  }
  // The probability that sample_light at (p, n) chooses light i.
  float light_pmf(const Vec3& p, const Vec3& n, size_t i) const { return light_sampler_.pmf(p, n, i); }
  // Chooses a light to emit a photon, in proportion to its power (times its sampling weight).
  const Light* sample_photon_light(float u, float& pmf) const;
  float photon_light_pmf(size_t i) const { return light_sampler_.pmf_by_power(i); }
  // Chooses a light for single scattering along a ray in a medium: by power half the time and
  // uniformly the other half (a defensive mixture; pmf the mixture's). By power alone, a small
  // lamp inside a fog ball under an environment is chosen 2 % of the time and then weighs 50
  // times its share: specks.
  const Light* sample_light_defensive(float u, float& pmf) const;
  // Radiance that the surface at `hit` emits towards local direction wo (its area light's, front
  // side only).
  Color emitted(const SurfaceHit& hit, const Vec3& wo_local) const {
    return hit.light >= 0 && wo_local.z > 0 ? lights[size_t(hit.light)]->surface_radiance(hit.sp) : Color(0.0f);
  }
  // Radiance arriving along a ray that leaves the scene in direction dir (environment lights).
  Color escaped(const Vec3& dir) const;
  // The indices of those lights in `lights`.
  const std::vector<size_t>& environment() const { return environment_; }
  const Accelerator& accel() const { return *accel_; }
  // Replaces the ray-casting structure by wrap(the current one): instrumentation, such as a
  // benchmark recording the rays an integrator casts. The wrapper must cast the same rays.
  template <class Wrap>
  void wrap_accel(Wrap wrap) {
    accel_ = wrap(std::move(accel_));
  }
  Bounds bounds() const { return bounds_; }
  float surface_area() const;  // of all geometry

 private:
  std::unique_ptr<Accelerator> accel_ = std::make_unique<Bvh>();
  LightSampler light_sampler_;
  std::vector<size_t> environment_;  // indices of lights that escaped rays see
  bool has_masks_ = false;           // some material is not fully opaque everywhere
  bool intersect_opaque(const Ray& ray, SurfaceHit& hit) const;
  Bounds bounds_;
};

}  // namespace caustica
