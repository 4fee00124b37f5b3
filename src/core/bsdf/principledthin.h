// Mitsuba 3's `principledthin`: the thin-surface Disney BSDF (Burley 2015) as Mitsuba 3 writes
// it, the same seen from either side. A diffuse part (retro-reflection, flatness, sheen) that
// `diff_trans` (0 to 2) splits between reflection and Lambertian transmission, and, weighted by
// `spec_trans` alone (with spec_trans 0 there is no specular lobe at all, as in Mitsuba), a GGX
// reflection and an unbent GGX transmission of roughness scaled by 0.65 eta - 0.35, tinted by
// base_color. Every parameter may be a texture.
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/bsdf/principled_common.h"

namespace caustica {

struct PrincipledThinSettings : principled::Shared {
  principled::Param diff_trans, eta;
  float rate_reflect = 1, rate_transmit = 1, rate_diffuse = 1, rate_diffuse_transmit = 1;  // lobe sampling rates
};

class PrincipledThin final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  explicit PrincipledThin(const PrincipledThinSettings& s) : s_(s) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override;
  float glossy_roughness() const override { return s_.glossy_roughness(); }
  Color albedo(const ShadingPoint& sp = {}) const override;

 private:
  struct Local;  // the parameters at a shading point
  Local at(const ShadingPoint& sp) const;
  struct Geometry;  // what eval and pdf derive from the directions alone
  // wi towards the viewer and wo towards the light, as Mitsuba names them.
  static Geometry geometry(const Vec3& wi, const Vec3& wo);
  // Mitsuba's eval (f |cos wo|) and pdf.
  Color eval_m(const Geometry& g, const Local& l) const;
  float pdf_m(const Geometry& g, const Local& l) const;
  PrincipledThinSettings s_;
};

}  // namespace caustica
