// The BSDF family's table: one row a plugin.
#include "core/bsdf/registry.h"
#include "core/bsdf/blend.h"
#include "core/bsdf/conductor.h"
#include "core/bsdf/dielectric.h"
#include "core/bsdf/diffuse.h"
#include "core/bsdf/mask.h"
#include "core/bsdf/normalmap.h"
#include "core/bsdf/null.h"
#include "core/bsdf/phong.h"
#include "core/bsdf/plastic.h"
#include "core/bsdf/twosided.h"
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
      {"twosided", true, true, TwoSided::create, {"bsdf"}},
      {"blendbsdf", true, true, BlendBsdf::create, {"bsdf", "weight"}},
      {"normalmap", true, true, NormalMap::create, {"bsdf", "normalmap"}},
      // No emission on a mask or a null surface: light sampling would see an opaque light
      // that rays pass through.
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
