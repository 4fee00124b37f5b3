// The thin principled BSDF, after Mitsuba 3's principledthin.cpp, in our frame conventions.
#include "core/bsdf/principledthin.h"
#include "core/sampling.h"

namespace caustica {
using namespace principled;

struct PrincipledThin::Local {
  Color base, tint;
  float r, spec_trans, spec_tint, sheen, sheen_tint, flatness, d, eta;
  MicrofacetDistribution reflect, transmit;  // GGX of the reflection and of the transmission
};

PrincipledThin::Local PrincipledThin::at(const ShadingPoint& sp) const {
  const TexturePoint& uv = sp;
  auto value = [&](const Param& p) { return p.has ? p.at(uv) : 0.0f; };
  const float r = s_.roughness.at(uv), aniso = value(s_.anisotropic), eta = s_.eta.at(uv);
  Local l{s_.base_color.at(uv), Color(1.0f), r, value(s_.spec_trans), value(s_.spec_tint), value(s_.sheen),
          value(s_.sheen_tint), value(s_.flatness), 0.5f * value(s_.diff_trans), eta,
          ggx(r, aniso, s_.anisotropic.has), ggx((0.65f * eta - 0.35f) * r, aniso, s_.anisotropic.has)};
  l.tint = tint_of(l.base);
  return l;
}

namespace {
struct Choice {
  float reflect = 0, transmit = 0, diffuse = 0, diffuse_transmit = 0;
};
}  // namespace

// The symmetrised directions: wi turned up, wo with it; wo_r the transmitted one mirrored back
// up, and the half vector of wi and wo_r, shared by reflection and transmission.
struct PrincipledThin::Geometry {
  Vec3 wi, wo, wo_r, h;
  bool valid = false, reflect = false, refract = false;
};

PrincipledThin::Geometry PrincipledThin::geometry(const Vec3& wi_in, const Vec3& wo_in) {
  Geometry g;
  const float c = wi_in.z;
  if (c == 0.0f) return g;
  g.wi = mulsign(wi_in, c), g.wo = mulsign(wo_in, c);
  g.reflect = g.wo.z > 0.0f, g.refract = g.wo.z < 0.0f;
  g.wo_r = Vec3(g.wo.x, g.wo.y, std::abs(g.wo.z));
  g.h = glm::normalize(g.wi + g.wo_r);
  g.valid = std::isfinite(g.h.x);
  return g;
}

Color PrincipledThin::eval_m(const Geometry& g, const Local& l) const {
  if (!g.valid) return Color(0.0f);
  const Vec3 &wi = g.wi, &wo = g.wo, &h = g.h;
  const float ci = wi.z, co = wo.z;
  const bool reflect = g.reflect, refract = g.refract;
  const float St = l.spec_trans, d = l.d;
  Color f(0.0f);
  if (s_.spec_trans.has) {
    const float Fd = fresnel(glm::dot(wi, h), l.eta).F;
    if (St > 0.0f && reflect && compatible(h, wi, wo, ci, true)) {
      Color F(Fd);
      if (s_.spec_tint.has) F = (1.0f - l.spec_tint) * Fd + l.spec_tint * schlick(l.tint * r0_of(l.eta), glm::dot(wi, h), l.eta);
      const float G = smith_g1(l.reflect, wi, h) * smith_g1(l.reflect, wo, h);
      f += F * (St * l.reflect.D(h) * G / (4.0f * ci));
    }
    if (St > 0.0f && refract && compatible(h, wi, wo, ci, false)) {
      const float G = smith_g1(l.transmit, wi, h) * smith_g1(l.transmit, wo, h);
      f += l.base * (St * (1.0f - Fd) * l.transmit.D(h) * G / (4.0f * ci));
    }
  }
  if (reflect && St < 1.0f && d < 1.0f) {
    const float cos_d = glm::dot(h, wo);
    const float k = diffuse_factor(l.r, cos_d, std::abs(co), ci, l.flatness, s_.flatness.has);
    f += l.base * ((1.0f - St) * (1.0f - d) * kInvPi * k * co);
    if (s_.sheen.has && l.sheen > 0.0f) {
      const Color sheen_tint = sheen_colour(s_.sheen_tint, l.sheen_tint, l.tint);
      f += sheen_tint * (l.sheen * (1.0f - St) * (1.0f - d) * schlick_weight(std::abs(cos_d)) * std::abs(co));
    }
  }
  if (refract && St < 1.0f && d > 0.0f && s_.diff_trans.has) f += l.base * ((1.0f - St) * d * kInvPi * std::abs(co));
  return f;
}

namespace {
Choice choose(float St, float d, bool has_st, bool has_dt, const PrincipledThinSettings& s) {
  Choice c;
  c.reflect = has_st ? St * s.rate_reflect * 0.5f : 0.0f;
  c.transmit = has_st ? St * s.rate_transmit * 0.5f : 0.0f;
  c.diffuse = s.rate_diffuse * (1.0f - St) * (1.0f - d);
  c.diffuse_transmit = has_dt ? s.rate_diffuse_transmit * (1.0f - St) * d : 0.0f;
  const float sum = c.reflect + c.transmit + c.diffuse + c.diffuse_transmit;
  if (!(sum > 0.0f)) return Choice{};
  c.reflect /= sum, c.transmit /= sum, c.diffuse /= sum, c.diffuse_transmit /= sum;
  return c;
}
}  // namespace

float PrincipledThin::pdf_m(const Geometry& g, const Local& l) const {
  if (!g.valid) return 0.0f;
  const Vec3 &wi = g.wi, &wo = g.wo, &wo_r = g.wo_r, &h = g.h;
  const float co = wo.z;
  const bool reflect = g.reflect, refract = g.refract;
  const Choice ch = choose(l.spec_trans, l.d, s_.spec_trans.has, s_.diff_trans.has, s_);
  const float jacobian = 1.0f / (4.0f * std::abs(glm::dot(wo_r, h)));
  float p = 0.0f;
  if (s_.spec_trans.has && reflect && compatible(h, wi, wo, wi.z, true)) p += ch.reflect * visible_pdf(l.reflect, wi, h) * jacobian;
  if (s_.spec_trans.has && refract && compatible(h, wi, wo, wi.z, false)) p += ch.transmit * visible_pdf(l.transmit, wi, h) * jacobian;
  if (reflect) p += ch.diffuse * co * kInvPi;
  if (s_.diff_trans.has && refract) p += ch.diffuse_transmit * std::abs(co) * kInvPi;
  return std::isfinite(p) ? p : 0.0f;
}

Color PrincipledThin::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  if (wi.z == 0.0f) return Color(0.0f);
  return eval_m(geometry(wo, wi), at(sp)) / std::abs(wi.z);
}

float PrincipledThin::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const { return pdf_m(geometry(wo, wi), at(sp)); }

bool PrincipledThin::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  const float c = wo.z;  // Mitsuba's wi
  if (c == 0.0f) return false;
  const Local l = at(sp);
  const Vec3 wi = mulsign(wo, c);
  const Choice ch = choose(l.spec_trans, l.d, s_.spec_trans.has, s_.diff_trans.has, s_);
  Vec3 out;
  if (u_lobe < ch.reflect) {
    const Vec3 m = l.reflect.sample_visible(wi, u);
    out = caustica::reflect(wi, m);
    if (!compatible(m, wi, out, wi.z, true) || !(out.z > 0.0f)) return false;
    s.lobe = kBsdfGlossy | kBsdfReflection;
  } else if (u_lobe < ch.reflect + ch.transmit) {
    const Vec3 m = l.transmit.sample_visible(wi, u);
    out = caustica::reflect(wi, m);
    out.z = -out.z;
    if (!compatible(m, wi, out, wi.z, false) || !(out.z < 0.0f)) return false;
    s.lobe = kBsdfGlossy | kBsdfTransmission;
  } else if (!s_.diff_trans.has || u_lobe < ch.reflect + ch.transmit + ch.diffuse) {
    out = sample_cosine_hemisphere(u);
    s.lobe = kBsdfDiffuse | kBsdfReflection;
  } else {
    out = -sample_cosine_hemisphere(u);
    s.lobe = kBsdfDiffuse | kBsdfTransmission;
  }
  out = mulsign(out, c);
  const Geometry g = geometry(wo, out);
  s.pdf = pdf_m(g, l);
  if (!(s.pdf > 0.0f)) return false;
  s.weight = eval_m(g, l) / s.pdf;
  s.wi = out;
  s.delta = false;
  return is_finite(s.weight);
}

uint32_t PrincipledThin::flags() const {
  uint32_t f = kBsdfReflection | kBsdfGlossy;
  // The diffuse part is there unless spec_trans is the number 1.
  const bool all_specular = s_.spec_trans.has && !s_.spec_trans.value.texture && s_.spec_trans.value.value.x == 1.0f;
  if (!all_specular) f |= kBsdfDiffuse;
  if (s_.diff_trans.has || s_.spec_trans.has) f |= kBsdfTransmission;
  return f;
}

Color PrincipledThin::albedo(const ShadingPoint& sp) const {
  const Local l = at(sp);
  return glm::min(l.base * (1.0f - l.spec_trans) + Color(l.spec_trans), Color(1.0f));
}

std::unique_ptr<Bsdf> PrincipledThin::create(const Params& p) {
  PrincipledThinSettings s;
  static_cast<Shared&>(s) = Shared::read(p);
  s.diff_trans = read(p, "diff_trans", 0.0f, 0.0f, 2.0f);
  s.eta = read(p, "eta", 1.5f, 1e-3f, 100.0f);
  s.rate_reflect = float(p.number_in("specular_reflectance_sampling_rate", 1.0, 0.0, 1e6));
  s.rate_transmit = float(p.number_in("specular_transmittance_sampling_rate", 1.0, 0.0, 1e6));
  s.rate_diffuse = float(p.number_in("diffuse_reflectance_sampling_rate", 1.0, 0.0, 1e6));
  s.rate_diffuse_transmit = float(p.number_in("diffuse_transmittance_sampling_rate", 1.0, 0.0, 1e6));
  return std::make_unique<PrincipledThin>(s);
}

}  // namespace caustica
