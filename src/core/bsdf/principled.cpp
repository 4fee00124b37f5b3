// The principled BSDF, after Mitsuba 3's principled.cpp: the same lobes, weights, Fresnel
// terms, sampling probabilities and edge cases, written in our frame conventions.
#include "core/bsdf/principled.h"
#include "core/sampling.h"

namespace caustica {
using namespace principled;

namespace {
// GTR1, the clearcoat's distribution (Burley 2012), and its sampling.
float gtr1_d(const Vec3& m, float a) {
  const float a2 = a * a;
  const float d = (a2 - 1.0f) / (kPi * std::log(a2) * (1.0f + (a2 - 1.0f) * m.z * m.z));
  return d * m.z > 1e-20f ? d : 0.0f;
}
Vec3 gtr1_sample(const Vec2& u, float a) {
  const float a2 = a * a;
  const float cos2 = (1.0f - std::pow(a2, 1.0f - u.y)) / (1.0f - a2);
  const float cos_t = std::sqrt(std::clamp(cos2, 0.0f, 1.0f)), sin_t = std::sqrt(std::max(0.0f, 1.0f - cos2));
  const float phi = 2.0f * kPi * u.x;
  return Vec3(std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t);
}
// The clearcoat's masking: Smith's GGX G1 of a fixed alpha 0.25 (Mitsuba's clearcoat_G).
float clearcoat_g1(const Vec3& v, const Vec3& h) {
  if (glm::dot(v, h) * v.z <= 0.0f) return 0.0f;
  const float c = std::abs(v.z);
  if (c >= 1.0f) return 1.0f;
  const float tan2 = (1.0f - c * c) / (c * c);
  return 2.0f / (1.0f + std::sqrt(1.0f + 0.0625f * tan2));
}
}  // namespace

struct Principled::Local {
  Color base, tint;
  float r, metallic, spec_trans, spec_tint, sheen, sheen_tint, flatness, clearcoat, alpha_cc;
  float brdf, bsdf;  // the weights of the diffuse part and of the dielectric's transmission
  MicrofacetDistribution dist;
};

Principled::Local Principled::at(const ShadingPoint& sp) const {
  const TexturePoint& uv = sp;
  auto value = [&](const Param& p) { return p.has ? p.at(uv) : 0.0f; };
  const float r = s_.roughness.at(uv);
  Local l{s_.base_color.at(uv), Color(1.0f), r, value(s_.metallic), value(s_.spec_trans), value(s_.spec_tint),
          value(s_.sheen), value(s_.sheen_tint), value(s_.flatness), value(s_.clearcoat), 0.0f, 0.0f, 0.0f,
          ggx(r, value(s_.anisotropic), s_.anisotropic.has)};
  l.tint = tint_of(l.base);
  l.alpha_cc = 0.1f - 0.099f * s_.clearcoat_gloss.at(uv);
  l.brdf = (1.0f - l.metallic) * (1.0f - l.spec_trans);
  l.bsdf = (1.0f - l.metallic) * l.spec_trans;
  return l;
}

namespace {
// The lobes' selection probabilities (diffuse, clearcoat, transmission, reflection), for wi on
// the front side or inside, with the dielectric's Fresnel reflectance Fd at the microfacet.
struct Choice {
  float diffuse = 0, clearcoat = 0, transmit = 0, reflect = 0;
};
Choice choose(bool front, float Fd, float brdf, float bsdf, float clearcoat, bool has_st, bool has_cc, float rate_s,
              float rate_c, float rate_d) {
  Choice c;
  if (front) {
    c.reflect = rate_s * (1.0f - bsdf * (1.0f - Fd));
    c.transmit = has_st ? rate_s * bsdf * (1.0f - Fd) : 0.0f;
    c.clearcoat = has_cc ? 0.25f * clearcoat * rate_c : 0.0f;
    c.diffuse = brdf * rate_d;
  } else {
    c.reflect = Fd;
    c.transmit = has_st ? 1.0f - Fd : 0.0f;
  }
  const float sum = c.diffuse + c.clearcoat + c.transmit + c.reflect;
  if (!(sum > 0.0f)) return Choice{};
  c.diffuse /= sum, c.clearcoat /= sum, c.transmit /= sum, c.reflect /= sum;
  return c;
}
}  // namespace

// What eval and pdf both derive from the pair of directions: which side wi is on, whether wo is
// reflected or refracted, the (generalised) half vector turned up, the dielectric's Fresnel
// there, and whether the microfacet can reflect or refract wi into wo.
struct Principled::Geometry {
  Vec3 wi, wo;
  float ci = 0, co = 0, eta_p = 1, wih = 0, woh = 0, Fd = 0;
  bool valid = false, front = false, reflect = false, refract = false, cr = false, ct = false;
  Vec3 h{0.0f};
};

Principled::Geometry Principled::geometry(const Vec3& wi, const Vec3& wo) const {
  Geometry g;
  g.wi = wi, g.wo = wo;
  g.ci = wi.z, g.co = wo.z;
  if (g.ci == 0.0f) return g;
  g.front = g.ci > 0.0f, g.reflect = g.ci * g.co > 0.0f, g.refract = g.ci * g.co < 0.0f;
  g.eta_p = g.front ? s_.eta : 1.0f / s_.eta;
  const Vec3 h = glm::normalize(wi + (g.reflect ? 1.0f : g.eta_p) * wo);
  g.h = mulsign(h, h.z);
  if (!std::isfinite(g.h.x)) return g;
  g.wih = glm::dot(wi, g.h), g.woh = glm::dot(wo, g.h);
  g.Fd = fresnel(g.wih, s_.eta).F;
  g.cr = compatible(g.h, wi, wo, g.ci, true), g.ct = compatible(g.h, wi, wo, g.ci, false);
  g.valid = true;
  return g;
}

Color Principled::eval_m(const Geometry& g, const Local& l) const {
  if (!g.valid) return Color(0.0f);
  const Vec3 &wi = g.wi, &wo = g.wo, &h = g.h;
  const float ci = g.ci, co = g.co, eta_p = g.eta_p, wih = g.wih, woh = g.woh, Fd = g.Fd;
  const bool front = g.front, reflect = g.reflect, refract = g.refract, cr = g.cr, ct = g.ct;
  const float D = l.dist.D(h), G = smith_g1(l.dist, wi, h) * smith_g1(l.dist, wo, h);
  Color f(0.0f);
  if (reflect && cr && Fd > 0.0f) {
    Color Fp;
    if (front) {
      Fp = Color((1.0f - l.metallic) * (1.0f - l.spec_tint) * Fd);
      if (s_.metallic.has) Fp += l.metallic * schlick(l.base, wih, s_.eta);
      if (s_.spec_tint.has) {
        const float eta_it = wih >= 0.0f ? s_.eta : 1.0f / s_.eta;
        Fp += (1.0f - l.metallic) * l.spec_tint * schlick(l.tint * r0_of(eta_it), wih, s_.eta);
      }
    } else {
      Fp = Color(l.bsdf * Fd);
    }
    f += Fp * (D * G / (4.0f * std::abs(ci)));
  }
  if (s_.spec_trans.has && l.bsdf > 0.0f && refract && ct && Fd < 1.0f) {
    const float denom = wih + eta_p * woh;
    const float t = l.bsdf * (1.0f - Fd) * D * G * eta_p * eta_p * std::abs(wih * woh) / (std::abs(ci) * denom * denom);
    f += glm::sqrt(l.base) * t;
  }
  if (s_.clearcoat.has && l.clearcoat > 0.0f && reflect && cr && front) {
    const float Fcc = schlick(Color(0.04f), wih, s_.eta).x;
    f += Color(0.25f * l.clearcoat * Fcc * gtr1_d(h, l.alpha_cc) * clearcoat_g1(wi, h) * clearcoat_g1(wo, h) * std::abs(co));
  }
  if (l.brdf > 0.0f && reflect && front) {
    const float cos_d = glm::dot(h, wo);
    const float k = diffuse_factor(l.r, cos_d, std::abs(co), std::abs(ci), l.flatness, s_.flatness.has);
    f += l.base * (l.brdf * kInvPi * k * std::abs(co));
    if (s_.sheen.has && l.sheen > 0.0f && 1.0f - l.metallic > 0.0f) {
      const Color sheen_tint = sheen_colour(s_.sheen_tint, l.sheen_tint, l.tint);
      f += sheen_tint * (l.sheen * (1.0f - l.metallic) * schlick_weight(std::abs(cos_d)) * std::abs(co));
    }
  }
  return f;
}

float Principled::pdf_m(const Geometry& g, const Local& l) const {
  if (!g.valid) return 0.0f;
  const Vec3 &wi = g.wi, &h = g.h;
  const float ci = g.ci, co = g.co, eta_p = g.eta_p, wih = g.wih, woh = g.woh, Fd = g.Fd;
  const bool front = g.front, reflect = g.reflect, refract = g.refract, cr = g.cr, ct = g.ct;
  const Choice c = choose(front, Fd, l.brdf, l.bsdf, l.clearcoat, s_.spec_trans.has, s_.clearcoat.has, s_.rate_specular,
                          s_.rate_clearcoat, s_.rate_diffuse);
  const Vec3 wi_up = mulsign(wi, ci);
  float jacobian = 1.0f / (4.0f * std::abs(woh));
  if (s_.spec_trans.has && !reflect) {
    const float denom = wih + eta_p * woh;
    jacobian = eta_p * eta_p * std::abs(woh) / (denom * denom);
  }
  float p = 0.0f;
  const float vis = visible_pdf(l.dist, wi_up, h);
  if (reflect && cr) p += c.reflect * vis * jacobian;
  if (reflect) p += c.diffuse * co * kInvPi;
  if (s_.spec_trans.has && refract && ct) p += c.transmit * vis * jacobian;
  if (s_.clearcoat.has && reflect && cr) p += c.clearcoat * h.z * gtr1_d(h, l.alpha_cc) * jacobian;
  return std::isfinite(p) ? p : 0.0f;
}

Color Principled::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  if (wi.z == 0.0f) return Color(0.0f);
  return eval_m(geometry(wo, wi), at(sp)) / std::abs(wi.z);
}

float Principled::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const { return pdf_m(geometry(wo, wi), at(sp)); }

bool Principled::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  // In Mitsuba's names: wi = our wo (towards the viewer), the sampled wo = our wi.
  const Vec3& wi = wo;
  const float ci = wi.z;
  if (ci == 0.0f) return false;
  const Local l = at(sp);
  const bool front = ci > 0.0f;
  if (!front && l.bsdf == 0.0f) return false;
  const Vec3 wi_up = mulsign(wi, ci);
  const Vec3 m = l.dist.sample_visible(wi_up, u);
  const Fresnel fr = fresnel(glm::dot(wi, m), s_.eta);
  const Choice c = choose(front, fr.F, l.brdf, l.bsdf, l.clearcoat, s_.spec_trans.has, s_.clearcoat.has,
                          s_.rate_specular, s_.rate_clearcoat, s_.rate_diffuse);
  Vec3 out;
  if (u_lobe < c.diffuse) {
    out = sample_cosine_hemisphere(u);
    if (!(ci * out.z > 0.0f)) return false;
    s.lobe = kBsdfDiffuse | kBsdfReflection;
  } else if (u_lobe < c.diffuse + c.clearcoat) {
    const Vec3 mc = gtr1_sample(u, l.alpha_cc);
    out = caustica::reflect(wi, mc);
    if (!compatible(mc, wi, out, ci, true) || !(ci * out.z > 0.0f)) return false;
    s.lobe = kBsdfGlossy | kBsdfReflection;
  } else if (u_lobe < c.diffuse + c.clearcoat + c.transmit) {
    out = refract(wi, m, fr);
    if (!compatible(m, wi, out, ci, false) || !(ci * out.z < 0.0f)) return false;
    s.lobe = kBsdfGlossy | kBsdfTransmission;
  } else {
    out = caustica::reflect(wi, m);
    if (!compatible(m, wi, out, ci, true) || !(ci * out.z > 0.0f)) return false;
    s.lobe = kBsdfGlossy | kBsdfReflection;
  }
  const Geometry g = geometry(wi, out);
  s.pdf = pdf_m(g, l);
  if (!(s.pdf > 0.0f)) return false;
  s.weight = eval_m(g, l) / s.pdf;
  s.wi = out;
  s.delta = false;
  return is_finite(s.weight);
}

uint32_t Principled::flags() const {
  uint32_t f = kBsdfGlossy | kBsdfReflection;
  // The diffuse part is there unless metallic or spec_trans is the number 1.
  auto is_one = [](const Param& p) { return p.has && !p.value.texture && p.value.value.x == 1.0f; };
  if (!is_one(s_.metallic) && !is_one(s_.spec_trans)) f |= kBsdfDiffuse;
  if (s_.spec_trans.has) f |= kBsdfTransmission;
  return f;
}

float Principled::refraction_eta(const Vec3& wo, const ShadingPoint&) const {
  if (!s_.spec_trans.has) return 1.0f;
  return wo.z > 0.0f ? s_.eta : 1.0f / s_.eta;
}

Color Principled::albedo(const ShadingPoint& sp) const {
  // An estimate: the diffuse part, the metal's base colour, the transmission's tint, and a
  // dielectric's reflectance at normal incidence.
  const Local l = at(sp);
  const Color a = l.brdf * l.base + l.metallic * l.base + l.bsdf * glm::sqrt(l.base) +
                  Color((1.0f - l.metallic) * r0_of(s_.eta));
  return glm::min(a, Color(1.0f));
}

std::unique_ptr<Bsdf> Principled::create(const Params& p) {
  PrincipledSettings s;
  static_cast<Shared&>(s) = Shared::read(p);
  s.metallic = read(p, "metallic", 0.0f, 0.0f, 1.0f);
  s.clearcoat = read(p, "clearcoat", 0.0f, 0.0f, 1.0f);
  s.clearcoat_gloss = read(p, "clearcoat_gloss", 0.0f, 0.0f, 1.0f);
  if (p.has("eta") && p.has("specular")) p.fail("specular", "give eta or specular, not both");
  if (p.has("eta")) {
    s.eta = float(p.number_in("eta", 1.5, 1e-3, 100.0));
    if (s.spec_trans.has && s.eta == 1.0f) s.eta = 1.001f;
  } else {
    float spec = float(p.number_in("specular", 0.5, 0.0, 1.0));
    if (s.spec_trans.has && spec == 0.0f) spec = 1e-3f;
    s.eta = 2.0f / (1.0f - std::sqrt(0.08f * spec)) - 1.0f;
  }
  s.rate_specular = float(p.number_in("main_specular_sampling_rate", 1.0, 0.0, 1e6));
  s.rate_clearcoat = float(p.number_in("clearcoat_sampling_rate", 1.0, 0.0, 1e6));
  s.rate_diffuse = float(p.number_in("diffuse_reflectance_sampling_rate", 1.0, 0.0, 1e6));
  return std::make_unique<Principled>(s);
}

}  // namespace caustica
