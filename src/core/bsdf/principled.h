// Mitsuba 3's `principled`: the Disney BSDF (Burley 2012, 2015) as Mitsuba 3 writes it. A
// diffuse base with retro-reflection (blended towards a fake subsurface term by `flatness`),
// sheen, a GGX specular lobe whose Fresnel mixes the dielectric's, a metal's (Schlick from
// base_color, by `metallic`) and a tinted one (`spec_tint`), GGX transmission (`spec_trans`,
// tinted by sqrt(base_color)), and a GTR1 clearcoat. Seen from below (inside), only the
// dielectric's reflection and transmission remain. Every parameter but eta and specular may be
// a texture. As in our other dielectrics, weights are the adjoint's; eye paths scale transmitted
// radiance by 1 / eta^2 (radiance_scale).
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/bsdf/principled_common.h"

namespace caustica {

struct PrincipledSettings : principled::Shared {
  principled::Param metallic, clearcoat, clearcoat_gloss;
  float eta = 1.5f;
  float rate_specular = 1, rate_clearcoat = 1, rate_diffuse = 1;  // lobe sampling rates
};

class Principled final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  explicit Principled(const PrincipledSettings& s) : s_(s) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override;
  float glossy_roughness() const override { return s_.glossy_roughness(); }
  Color albedo(const ShadingPoint& sp = {}) const override;
  float refraction_eta(const Vec3& wo, const ShadingPoint& = {}) const override;

 private:
  struct Local;  // the parameters at a shading point
  Local at(const ShadingPoint& sp) const;
  struct Geometry;  // what eval and pdf derive from the directions alone
  // wi towards the viewer and wo towards the light, as Mitsuba names them.
  Geometry geometry(const Vec3& wi, const Vec3& wo) const;
  // Mitsuba's eval (f |cos wo|) and pdf.
  Color eval_m(const Geometry& g, const Local& l) const;
  float pdf_m(const Geometry& g, const Local& l) const;
  PrincipledSettings s_;
};

}  // namespace caustica
