// What several BSDF plugins read alike.
#include "core/bsdf/bsdf_params.h"
#include "core/bsdf/ior.h"

namespace caustica {

float read_ior(const Params& p, const std::string& key, float fallback) {
  if (!p.has(key)) return fallback;
  if (p.is_string(key)) {
    const std::string name = p.string(key, "");
    float v;
    if (!lookup_dielectric_ior(name, v)) {
      p.fail(key, "unknown index of refraction \"" + name + "\" (known: " + known_dielectrics() + ")");
    }
    return v;
  }
  const double v = p.number(key, 0.0);
  if (!(v > 0.0)) p.fail(key, "index of refraction must be positive");
  return float(v);
}

float read_eta(const Params& p, float int_default) {
  return read_ior(p, "int_ior", int_default) / read_ior(p, "ext_ior", 1.000277f);
}

MicrofacetType read_distribution_type(const Params& p) {
  MicrofacetType type = MicrofacetType::GGX;
  if (p.has("distribution")) {
    const std::string d = p.string("distribution", "");
    if (d == "beckmann") type = MicrofacetType::Beckmann;
    else if (d != "ggx") p.fail("distribution", "unknown distribution \"" + d + "\" (known: ggx, beckmann)");
  }
  return type;
}

MicrofacetDistribution read_distribution(const Params& p) {
  const MicrofacetType type = read_distribution_type(p);
  if (p.has("alpha") && (p.has("alpha_u") || p.has("alpha_v"))) p.fail("", "give either alpha or alpha_u and alpha_v");
  if (p.has("alpha_u") != p.has("alpha_v")) p.fail("", "alpha_u and alpha_v go together");
  const float a = float(p.number_in("alpha", 0.1, 0.0, 4.0));
  return MicrofacetDistribution(type, float(p.number_in("alpha_u", a, 0.0, 4.0)), float(p.number_in("alpha_v", a, 0.0, 4.0)));
}

Roughness read_roughness(const Params& p) {
  bool textured = false;
  for (const char* key : {"alpha", "alpha_u", "alpha_v"}) textured = textured || (p.has(key) && p.texture(key, Color(0.1f)).texture);
  if (!textured) return read_distribution(p);
  const MicrofacetType type = read_distribution_type(p);
  if (p.has("alpha") && (p.has("alpha_u") || p.has("alpha_v"))) p.fail("", "give either alpha or alpha_u and alpha_v");
  if (p.has("alpha_u") != p.has("alpha_v")) p.fail("", "alpha_u and alpha_v go together");
  auto alpha = [&](const char* key) {
    const ColorParam a = p.texture(key, Color(0.1f));
    if (!a.texture && !(a.value.x >= 0.0f && a.value.x <= 4.0f && a.value.y == a.value.x && a.value.z == a.value.x)) {
      p.fail(key, std::string(key) + " must be one number from 0 to 4, or a texture");
    }
    return a;
  };
  if (p.has("alpha")) {
    const ColorParam a = alpha("alpha");
    return Roughness(type, a, a);
  }
  return Roughness(type, alpha("alpha_u"), alpha("alpha_v"));
}

ConductorIor read_conductor(const Params& p) {
  ConductorIor ior;
  if (p.has("material") && (p.has("eta") || p.has("k"))) p.fail("", "give either material or eta and k");
  if (p.has("material")) {
    const std::string name = p.string("material", "");
    if (!lookup_conductor(name, ior)) {
      p.fail("material", "unknown conductor \"" + name + "\" (known: " + known_conductors() + ")");
    }
  } else if (p.has("eta") || p.has("k")) {
    if (!p.has("eta") || !p.has("k")) p.fail("", "eta and k go together");
    ior.eta = p.color("eta", Color(0.0f));
    ior.k = p.color("k", Color(0.0f));
    if (!(ior.eta.x > 0 && ior.eta.y > 0 && ior.eta.z > 0)) p.fail("eta", "eta must be positive");
  }
  return ior;
}

DielectricTint read_dielectric_tint(const Params& p) {
  DielectricTint t;
  t.reflect = p.texture("specular_reflectance", Color(1.0f));
  t.transmit = p.texture("specular_transmittance", Color(1.0f));
  check_albedo(p, "specular_reflectance", t.reflect);
  check_albedo(p, "specular_transmittance", t.transmit);
  return t;
}

void check_albedo(const Params& p, const std::string& key, const ColorParam& c) {
  if (!c.texture && max_component(c.value) > 1.0f) {
    p.warn(key, key + " above 1 reflects more than it receives (energy is created)");
  }
}

}  // namespace caustica
