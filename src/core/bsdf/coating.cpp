// Smooth and rough dielectric coatings over a nested BSDF.
#include "core/bsdf/coating.h"
#include <tbb/parallel_for.h>
#include "core/bsdf/bsdf_params.h"
#include "core/bsdf/diffuse.h"
#include "core/bsdf/fresnel.h"

namespace caustica {

Coating::Coating(const Bsdf* nested, float eta, float thickness, const ColorParam& sigma_a, const ColorParam& specular,
                 std::optional<MicrofacetDistribution> dist)
    : nested_(nested), eta_(eta), thickness_(thickness), sigma_a_(sigma_a), specular_(specular), dist_(dist) {
  // Mitsuba's weight of the layer in choosing what to sample: 1 / (1 + the mean transmittance
  // of a trip down and up through the layer at normal incidence).
  const Color sa = sigma_a_.at(Vec2(0.5f));
  const float mean = (std::exp(-2.0f * thickness_ * sa.x) + std::exp(-2.0f * thickness_ * sa.y) +
                      std::exp(-2.0f * thickness_ * sa.z)) / 3.0f;
  layer_weight_ = 1.0f / (1.0f + mean);
  if (dist_) {
    rough_transmittance_.v.resize(CosineTable::kSize + 1);
    tbb::parallel_for(0, CosineTable::kSize + 1, [&](int k) {
      rough_transmittance_.v[size_t(k)] = float(rough_boundary(*dist_, float(k) / CosineTable::kSize, eta_).second);
    });
  }
}

bool Coating::refract_in(const Vec3& w, Vec3& inside) const {
  const float z2 = 1.0f - (1.0f - w.z * w.z) / (eta_ * eta_);
  if (!(z2 > 0.0f)) return false;
  inside = Vec3(w.x / eta_, w.y / eta_, std::copysign(std::sqrt(z2), w.z));
  return true;
}

bool Coating::refract_out(const Vec3& inside, Vec3& w) const {
  const float z2 = 1.0f - (1.0f - inside.z * inside.z) * eta_ * eta_;
  if (!(z2 > 0.0f)) return false;
  w = Vec3(eta_ * inside.x, eta_ * inside.y, std::copysign(std::sqrt(z2), inside.z));
  return true;
}

float Coating::transmittance(float cos_theta) const {
  const float c = std::clamp(cos_theta, 0.0f, 1.0f);
  return dist_ ? rough_transmittance_(c) : 1.0f - fresnel_dielectric(c, eta_);
}

float Coating::surface_probability(float cos_o) const {
  const float r = 1.0f - transmittance(cos_o), w = layer_weight_;
  const float denom = r * w + (1.0f - r) * (1.0f - w);
  return denom > 0.0f ? r * w / denom : 0.0f;
}

Color Coating::absorption(const Vec3& a, const Vec3& b, const ShadingPoint& sp) const {
  if (sigma_a_.is_black() || thickness_ == 0.0f) return Color(1.0f);
  const Color sa = sigma_a_.at(sp);
  const float path = thickness_ * (1.0f / std::abs(a.z) + 1.0f / std::abs(b.z));
  return glm::exp(-sa * path);
}

Color Coating::surface_eval(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (!dist_ || wo_in.z * wi_in.z <= 0.0f) return Color(0.0f);
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  const Vec3 h = glm::normalize(wo + wi);
  const float d = dist_->D(h);
  if (!(d > 0.0f)) return Color(0.0f);
  const float F = fresnel_dielectric(std::abs(glm::dot(wo, h)), eta_);
  return specular_.at(sp) * (F * d * dist_->G1(wo) * dist_->G1(wi) / (4.0f * wo.z * wi.z));
}

float Coating::surface_pdf(const Vec3& wo, const Vec3& wi) const { return dist_ ? reflection_pdf(*dist_, wo, wi) : 0.0f; }

Color Coating::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  Color f = surface_eval(wo, wi, sp);
  Vec3 a, b;
  if (refract_in(wo, a) && refract_in(wi, b)) {
    const Color n = nested_->eval(a, b, sp);
    if (!is_black(n)) {
      f += n * absorption(a, b, sp) * (transmittance(std::abs(wo.z)) * transmittance(std::abs(wi.z)) / (eta_ * eta_));
    }
  }
  return f;
}

float Coating::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const float ps = surface_probability(std::abs(wo.z));
  float p = dist_ ? ps * surface_pdf(wo, wi) : 0.0f;
  Vec3 a, b;
  if (wi.z != 0.0f && refract_in(wo, a) && refract_in(wi, b)) {
    // The nested density in the layer's solid angle, times d omega' / d omega = cos / (eta^2 cos').
    p += (1.0f - ps) * nested_->pdf(a, b, sp) * std::abs(wi.z) / (eta_ * eta_ * std::abs(b.z));
  }
  return p;
}

bool Coating::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  if (wo.z == 0.0f) return false;
  const float ps = surface_probability(std::abs(wo.z));
  if (u_lobe < ps) {
    if (!dist_) {
      s.wi = reflect_local(wo);
      s.weight = specular_.at(sp) * (fresnel_dielectric(std::abs(wo.z), eta_) / ps);
      s.pdf = 0.0f;
      s.delta = true;
      s.lobe = kBsdfSpecular | kBsdfReflection;
      return true;
    }
    const bool below = wo.z < 0.0f;
    const Vec3 wo_up = below ? flip_z(wo) : wo;
    const Vec3 wi = reflect(wo_up, dist_->sample_visible(wo_up, u));
    if (!(wi.z > 0.0f)) return false;
    return complete_sample(*this, wo_up, wi, kBsdfGlossy | kBsdfReflection, below, sp, s);
  }
  Vec3 a;
  if (!refract_in(wo, a)) return false;
  BsdfSample ns;
  if (!nested_->sample(a, u, std::min((u_lobe - ps) / (1.0f - ps), 0.99999994f), ns, sp)) return false;
  Vec3 wi;
  if (!refract_out(ns.wi, wi)) return false;
  if (ns.delta) {
    s.weight = ns.weight * absorption(a, ns.wi, sp) *
               (transmittance(std::abs(wo.z)) * transmittance(std::abs(wi.z)) / (1.0f - ps));
    s.wi = wi;
    s.pdf = 0.0f;
    s.delta = true;
    s.lobe = ns.lobe;
    return true;
  }
  s.pdf = pdf(wo, wi, sp);
  if (!(s.pdf > 0.0f)) return false;
  s.weight = eval(wo, wi, sp) * (std::abs(wi.z) / s.pdf);
  s.wi = wi;
  s.delta = false;
  s.lobe = ns.lobe;
  return is_finite(s.weight);
}

int Coating::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  if (wo.z == 0.0f) return 0;
  // The surface's mirror (for the rough surface, its smooth limit), then the nested BSDF's
  // delta lobes through the layer, as many as fit.
  int n = 0;
  out[n].wi = reflect_local(wo);
  out[n].weight = specular_.at(sp) * fresnel_dielectric(std::abs(wo.z), eta_);
  out[n].pdf = 0.0f;
  out[n].delta = true;
  out[n++].lobe = kBsdfSpecular | kBsdfReflection;
  Vec3 a;
  BsdfSample inner[2];
  // (Only true delta lobes: a glossy BSDF's specular_lobes are its smooth limit.) More than
  // two in all (glass under the coat): none listed, as the contract above has no room for them.
  const int k = nested_->has(kBsdfSpecular) && refract_in(wo, a) ? nested_->specular_lobes(a, inner, sp) : 0;
  for (int i = 0; i < k; ++i) {
    Vec3 wi;
    if (!refract_out(inner[i].wi, wi)) continue;
    if (n == 2) return 0;
    out[n] = inner[i];
    out[n].wi = wi;
    out[n++].weight = inner[i].weight * absorption(a, inner[i].wi, sp) *
                      (transmittance(std::abs(wo.z)) * transmittance(std::abs(wi.z)));
  }
  return n;
}

uint32_t Coating::flags() const { return nested_->flags() | kBsdfReflection | (dist_ ? kBsdfGlossy : kBsdfSpecular); }

float Coating::glossy_roughness() const {
  if (!dist_) return nested_->glossy_roughness();
  const float a = std::min(dist_->alpha_u(), dist_->alpha_v());
  return nested_->has(kBsdfGlossy) ? std::min(a, nested_->glossy_roughness()) : a;
}

Color Coating::albedo(const ShadingPoint& sp) const {
  const float t = transmittance(1.0f);
  const Color trip = glm::exp(-2.0f * thickness_ * sigma_a_.at(sp));
  return glm::min(specular_.at(sp) * (1.0f - t) + nested_->albedo(sp) * trip * (t * t), Color(1.0f));
}

namespace {
// What both plugins read: the nested BSDF, the indices (Mitsuba 0.6's defaults: bk7 in air),
// the layer's thickness and absorption, and the surface's tint.
struct LayerParams {
  const Bsdf* nested;
  float eta, thickness;
  ColorParam sigma_a, specular;
};
LayerParams read_layer(const Params& p) {
  LayerParams l;
  l.nested = p.bsdfs("bsdf", false).front();
  l.eta = read_eta(p, 1.5046f);
  if (l.eta == 1.0f) p.fail("int_ior", "the coating's int_ior equals its ext_ior: there is no coating");
  l.thickness = float(p.number_in("thickness", 1.0, 0.0, 1e9));
  l.sigma_a = p.texture("sigma_a", Color(0.0f));
  l.specular = p.texture("specular_reflectance", Color(1.0f));
  check_albedo(p, "specular_reflectance", l.specular);
  return l;
}
}  // namespace

std::unique_ptr<Bsdf> Coating::create(const Params& p) {
  const LayerParams l = read_layer(p);
  return std::make_unique<Coating>(l.nested, l.eta, l.thickness, l.sigma_a, l.specular, std::nullopt);
}

std::unique_ptr<Bsdf> Coating::create_rough(const Params& p) {
  if (p.has("alpha_u") || p.has("alpha_v")) p.fail("alpha_u", "roughcoating is isotropic: give alpha");
  const LayerParams l = read_layer(p);
  return std::make_unique<Coating>(l.nested, l.eta, l.thickness, l.sigma_a, l.specular, read_distribution(p));
}

}  // namespace caustica
