// The BSDF family's table: one row a plugin.
#include "core/bsdf/registry.h"
#include "core/bsdf/blend.h"
#include "core/bsdf/bumpmap.h"
#include "core/bsdf/coating.h"
#include "core/bsdf/conductor.h"
#include "core/bsdf/dielectric.h"
#include "core/bsdf/diffuse.h"
#include "core/bsdf/mask.h"
#include "core/bsdf/normalmap.h"
#include "core/bsdf/null.h"
#include "core/bsdf/phong.h"
#include "core/bsdf/plastic.h"
#include "core/bsdf/principled.h"
#include "core/bsdf/principledthin.h"
#include "core/bsdf/twosided.h"
#include "core/bsdf/ward.h"
#include "core/registry.h"

namespace caustica {

const std::vector<BsdfPlugin>& bsdf_plugins() {
  static const std::vector<BsdfPlugin> table = {
      {"diffuse", true, true, Lambertian::create, {"reflectance", "albedo"}},
      {"conductor", true, true, Conductor::create, {"material", "eta", "k", "specular_reflectance"}},
      {"roughconductor", true, true, RoughConductor::create,
       {"material", "eta", "k", "specular_reflectance", "distribution", "alpha", "alpha_u", "alpha_v"}},
      {"dielectric", true, true, Dielectric::create, {"int_ior", "ext_ior", "specular_reflectance", "specular_transmittance"}},
      {"thindielectric", true, true, ThinDielectric::create,
       {"int_ior", "ext_ior", "specular_reflectance", "specular_transmittance"}},
      {"roughdielectric", true, true, RoughDielectric::create,
       {"int_ior", "ext_ior", "distribution", "alpha", "alpha_u", "alpha_v", "specular_reflectance", "specular_transmittance"}},
      {"plastic", true, true, Plastic::create,
       {"diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear"}},
      {"roughplastic", true, true, Plastic::create_rough,
       {"diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear", "distribution", "alpha"}},
      {"phong", true, true, Phong::create, {"diffuse_reflectance", "specular_reflectance", "exponent"}},
      {"principled", true, true, Principled::create,
       {"base_color", "roughness", "anisotropic", "metallic", "spec_trans", "eta", "specular", "spec_tint", "sheen",
        "sheen_tint", "flatness", "clearcoat", "clearcoat_gloss", "main_specular_sampling_rate", "clearcoat_sampling_rate",
        "diffuse_reflectance_sampling_rate"}},
      {"principledthin", true, true, PrincipledThin::create,
       {"base_color", "roughness", "anisotropic", "spec_trans", "eta", "spec_tint", "sheen", "sheen_tint", "flatness",
        "diff_trans", "specular_reflectance_sampling_rate", "specular_transmittance_sampling_rate",
        "diffuse_reflectance_sampling_rate", "diffuse_transmittance_sampling_rate"}},
      {"twosided", true, true, TwoSided::create, {"bsdf"}},
      {"blendbsdf", true, true, BlendBsdf::create, {"bsdf", "weight"}},
      {"normalmap", true, true, NormalMap::create, {"bsdf", "normalmap"}},
      {"bumpmap", true, true, BumpMap::create, {"bsdf", "height", "scale"}},
      // No emission on a mask or a null surface: light sampling would see an opaque light
      // that rays pass through.
      {"coating", true, true, Coating::create, {"bsdf", "int_ior", "ext_ior", "thickness", "sigma_a", "specular_reflectance"}},
      {"roughcoating", true, true, Coating::create_rough,
       {"bsdf", "int_ior", "ext_ior", "thickness", "sigma_a", "specular_reflectance", "distribution", "alpha"}},
      {"ward", true, true, Ward::create,
       {"variant", "alpha", "alpha_u", "alpha_v", "specular_reflectance", "diffuse_reflectance", "ensure_energy_conservation"}},
      {"mask", true, false, Mask::create, {"bsdf", "opacity"}},
      {"null", true, false, NullBsdf::create, {}},
      {"mirror", false, true, Conductor::create_mirror, {"reflectance"}},
      {"glass", false, true, Dielectric::create_glass, {"ior", "fresnel"}},
  };
  return table;
}

const BsdfPlugin* find_bsdf_plugin(const std::string& name) { return find_plugin(bsdf_plugins(), name); }

std::string known_bsdfs() { return plugin_names(bsdf_plugins()); }

}  // namespace caustica
