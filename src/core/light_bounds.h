// Where a light's emission can reach and how strongly: a box around its emitting points, a cone
// around their normals (or a spot's axis), and its power. The spatial light sampler
// (core/light_sampler.h) builds a tree of these and weighs each subtree by its importance at a
// shading point, as pbrt-v4's LightBounds and BVHLightSampler (Conty Estevez and Kulla 2018).
#pragma once
#include "core/shape.h"

namespace caustica {

// A cone of directions around a unit axis with half-angle acos(cos_theta) (-1: every direction).
struct DirectionCone {
  Vec3 axis{0.0f, 0.0f, 1.0f};
  float cos_theta = -1.0f;
  static DirectionCone everywhere() { return {}; }
  // The smallest cone that holds both (exact for two cones; for many, a bound).
  static DirectionCone unite(const DirectionCone& a, const DirectionCone& b);
};

struct LightBounds {
  Bounds bounds;       // the emitting points (a point light's position)
  DirectionCone normals;  // their normals (a spot's or projector's axis and half-angle)
  // How far past a normal light still leaves: pi/2 (cos 0) for a surface emitting by cosine,
  // 0 (cos 1) for a spot that sends nothing outside its cone.
  float cos_theta_e = 0.0f;
  float phi = 0.0f;  // power (luminance-like scalar) times the light's sampling weight

  // An estimate of the light reaching p, a point with normal n (zero: no normal), from anything
  // these bounds hold: phi over the squared distance, times the cosine of the least angle
  // between the emitting cone and p's direction and, with a normal, of the least angle of
  // incidence. Zero only where no point and direction of the bounds can light p.
  float importance(const Vec3& p, const Vec3& n) const;
  static LightBounds unite(const LightBounds& a, const LightBounds& b);
};

}  // namespace caustica
