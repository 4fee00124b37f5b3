// Material blocks: diffuse, conductor, roughconductor, dielectric, thindielectric,
// roughdielectric, phong, twosided, plus our aliases mirror and glass.
#include "io/bsdf_reader.h"
#include "core/bsdf/conductor.h"
#include "core/bsdf/dielectric.h"
#include "core/bsdf/diffuse.h"
#include "core/bsdf/ior.h"
#include "core/bsdf/mask.h"
#include "core/bsdf/phong.h"
#include "core/bsdf/plastic.h"
#include "core/bsdf/twosided.h"
#include "io/texture_reader.h"

namespace caustica {
namespace {
using nlohmann::json;

struct Block {
  const MaterialContext& ctx;
  const JsonReader& r;
  const json& m;
  const std::string& p;
  bool has(const char* key) const { return m.contains(key); }
  std::string at(const char* key) const { return child(p, key); }
  Color color(const char* key, const Color& fallback) const {
    return has(key) ? r.color(m[key], at(key)) : fallback;
  }
  // A colour that may also be a texture block.
  ColorParam param(const char* key, const Color& fallback) const {
    if (!has(key)) return fallback;
    if (!m[key].is_object()) return r.color(m[key], at(key));
    ctx.textures.push_back(read_texture(ctx, m[key], at(key)));
    return ColorParam(ctx.textures.back().get());
  }
  float number(const char* key, float fallback, double lo, double hi) const {
    return has(key) ? float(r.number_in(m[key], at(key), lo, hi)) : fallback;
  }
  // An index of refraction: a number or a name from Mitsuba's table.
  float ior(const char* key, float fallback) const {
    if (!has(key)) return fallback;
    if (m[key].is_string()) {
      const std::string name = r.string(m[key], at(key));
      float v;
      if (!lookup_dielectric_ior(name, v)) {
        r.fail(at(key), "unknown index of refraction \"" + name + "\" (known: " + known_dielectrics() + ")");
      }
      return v;
    }
    const double v = r.number(m[key], at(key));
    if (!(v > 0.0)) r.fail(at(key), "index of refraction must be positive");
    return float(v);
  }
  // int_ior / ext_ior, the relative index of the interior.
  float eta(float int_default) const {
    return ior("int_ior", int_default) / ior("ext_ior", 1.000277f);
  }
  MicrofacetDistribution distribution() const {
    MicrofacetType type = MicrofacetType::GGX;
    if (has("distribution")) {
      const std::string d = r.string(m["distribution"], at("distribution"));
      if (d == "beckmann") type = MicrofacetType::Beckmann;
      else if (d != "ggx") r.fail(at("distribution"), "unknown distribution \"" + d + "\" (known: ggx, beckmann)");
    }
    if (has("alpha") && (has("alpha_u") || has("alpha_v"))) r.fail(p, "give either alpha or alpha_u and alpha_v");
    if (has("alpha_u") != has("alpha_v")) r.fail(p, "alpha_u and alpha_v go together");
    const float a = number("alpha", 0.1f, 0.0, 4.0);
    return MicrofacetDistribution(type, number("alpha_u", a, 0.0, 4.0), number("alpha_v", a, 0.0, 4.0));
  }
  ConductorIor conductor() const {
    ConductorIor ior;  // default: Mitsuba's "none", a perfect mirror
    if (has("material") && (has("eta") || has("k"))) r.fail(p, "give either material or eta and k");
    if (has("material")) {
      const std::string name = r.string(m["material"], at("material"));
      if (!lookup_conductor(name, ior)) {
        r.fail(at("material"), "unknown conductor \"" + name + "\" (known: " + known_conductors() + ")");
      }
    } else if (has("eta") || has("k")) {
      if (!has("eta") || !has("k")) r.fail(p, "eta and k go together");
      ior.eta = r.color(m["eta"], at("eta"));
      ior.k = r.color(m["k"], at("k"));
      if (!(ior.eta.x > 0 && ior.eta.y > 0 && ior.eta.z > 0)) r.fail(at("eta"), "eta must be positive");
    }
    return ior;
  }
};

void check_albedo(const Block& b, const char* key, const ColorParam& c, std::vector<std::string>& warnings) {
  if (!c.texture && max_component(c.value) > 1.0f) {
    b.r.warn(b.at(key), std::string(key) + " above 1 reflects more than it receives (energy is created)", warnings);
  }
}

}  // namespace

const char* known_material_types() {
  return "diffuse, conductor, roughconductor, dielectric, thindielectric, roughdielectric, plastic, roughplastic, "
         "phong, twosided, mask, mirror, glass";
}

std::unique_ptr<Material> read_material(const MaterialContext& ctx, const json& m, const std::string& p) {
  const JsonReader& r = ctx.r;
  std::vector<std::string>& warnings = ctx.warnings;
  if (!m.is_object()) r.fail(p, "expected an object");
  const Block b{ctx, r, m, p};
  const std::string type = r.string(r.require(m, p, "type"), child(p, "type"));
  std::unique_ptr<Material> mat;
  if (type == "diffuse") {
    r.check_object(m, p, {"type", "reflectance", "albedo", "emission"});
    if (b.has("reflectance") && b.has("albedo")) r.fail(p, "albedo is an alias of reflectance: give one");
    const ColorParam rho = b.param(b.has("albedo") ? "albedo" : "reflectance", Color(0.5f));
    check_albedo(b, b.has("albedo") ? "albedo" : "reflectance", rho, warnings);
    mat = std::make_unique<Lambertian>(rho);
  } else if (type == "mirror") {
    r.check_object(m, p, {"type", "reflectance", "emission"});
    mat = std::make_unique<Conductor>(ConductorIor{}, b.param("reflectance", Color(1.0f)));
  } else if (type == "conductor") {
    r.check_object(m, p, {"type", "material", "eta", "k", "specular_reflectance", "emission"});
    mat = std::make_unique<Conductor>(b.conductor(), b.param("specular_reflectance", Color(1.0f)));
  } else if (type == "roughconductor") {
    r.check_object(m, p, {"type", "material", "eta", "k", "specular_reflectance", "distribution", "alpha",
                          "alpha_u", "alpha_v", "emission"});
    mat = std::make_unique<RoughConductor>(b.distribution(), b.conductor(), b.param("specular_reflectance", Color(1.0f)));
  } else if (type == "glass") {
    r.check_object(m, p, {"type", "ior", "fresnel", "emission"});
    const float ior = b.ior("ior", 1.5f);
    FresnelModel model = FresnelModel::Exact;
    if (b.has("fresnel")) {
      const std::string f = r.string(m["fresnel"], b.at("fresnel"));
      if (f == "schlick") model = FresnelModel::Schlick;
      else if (f != "exact") r.fail(b.at("fresnel"), "unknown Fresnel model \"" + f + "\" (known: exact, schlick)");
    }
    mat = std::make_unique<Dielectric>(ior, model);
  } else if (type == "dielectric") {
    r.check_object(m, p, {"type", "int_ior", "ext_ior", "emission"});
    mat = std::make_unique<Dielectric>(b.eta(1.5046f), FresnelModel::Exact);
  } else if (type == "thindielectric") {
    r.check_object(m, p, {"type", "int_ior", "ext_ior", "emission"});
    mat = std::make_unique<ThinDielectric>(b.eta(1.5046f));
  } else if (type == "roughdielectric") {
    r.check_object(m, p, {"type", "int_ior", "ext_ior", "distribution", "alpha", "alpha_u", "alpha_v", "emission"});
    mat = std::make_unique<RoughDielectric>(b.distribution(), b.eta(1.5046f));
  } else if (type == "plastic" || type == "roughplastic") {
    const bool rough = type == "roughplastic";
    if (rough) {
      r.check_object(m, p, {"type", "diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear",
                            "distribution", "alpha", "emission"});
    } else {
      r.check_object(m, p, {"type", "diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear", "emission"});
    }
    const ColorParam kd = b.param("diffuse_reflectance", Color(0.5f));
    check_albedo(b, "diffuse_reflectance", kd, warnings);
    const bool nonlinear = b.has("nonlinear") && r.boolean(m["nonlinear"], b.at("nonlinear"));
    std::optional<MicrofacetDistribution> dist;
    if (rough) dist = b.distribution();
    mat = std::make_unique<Plastic>(kd, b.param("specular_reflectance", Color(1.0f)), b.eta(1.49f), nonlinear, dist);
  } else if (type == "phong") {
    r.check_object(m, p, {"type", "diffuse_reflectance", "specular_reflectance", "exponent", "emission"});
    const ColorParam kd = b.param("diffuse_reflectance", Color(0.5f));
    const ColorParam ks = b.param("specular_reflectance", Color(0.2f));
    if (!kd.texture && !ks.texture && max_component(kd.value + ks.value) > 1.0f) {
      r.warn(p, "diffuse_reflectance + specular_reflectance above 1 creates energy", warnings);
    }
    mat = std::make_unique<Phong>(kd, ks, b.number("exponent", 30.0f, 0.0, 1e6));
  } else if (type == "mask") {
    // No emission on a mask: light sampling would see an opaque light that rays pass through.
    r.check_object(m, p, {"type", "bsdf", "opacity"});
    ctx.nested.push_back(read_material(ctx, r.require(m, p, "bsdf"), b.at("bsdf")));
    if (ctx.nested.back()->is_emissive()) r.fail(b.at("bsdf"), "a masked material cannot emit light");
    const ColorParam opacity = b.param("opacity", Color(0.5f));
    if (!opacity.texture && max_component(opacity.value) > 1.0f) r.fail(b.at("opacity"), "opacity must lie in [0, 1]");
    mat = std::make_unique<Mask>(ctx.nested.back().get(), opacity);
  } else if (type == "twosided") {
    r.check_object(m, p, {"type", "bsdf", "emission"});
    const json& inner = r.require(m, p, "bsdf");
    const std::string ip = b.at("bsdf");
    std::vector<const Material*> sides;
    if (inner.is_array()) {
      if (inner.size() != 1 && inner.size() != 2) r.fail(ip, "expected one BSDF, or two (front and back)");
      for (size_t i = 0; i < inner.size(); ++i) {
        ctx.nested.push_back(read_material(ctx, inner[i], child(ip, i)));
        sides.push_back(ctx.nested.back().get());
      }
    } else {
      ctx.nested.push_back(read_material(ctx, inner, ip));
      sides.push_back(ctx.nested.back().get());
    }
    for (size_t i = 0; i < sides.size(); ++i) {
      if (sides[i]->emission != Color(0.0f)) r.fail(ip, "emission belongs on the twosided material, not inside it");
    }
    mat = std::make_unique<TwoSided>(sides.front(), sides.back());
  } else {
    r.fail(child(p, "type"), "unknown material type \"" + type + "\" (known: " + known_material_types() + ")");
  }
  if (b.has("emission")) mat->emission = r.color(m["emission"], b.at("emission"));
  return mat;
}

}  // namespace caustica
