// What several BSDF plugins read alike: indices of refraction (a number or a name from
// Mitsuba's tables), the microfacet distribution, a conductor's complex index, and the warning
// for an albedo that creates energy.
#pragma once
#include "core/bsdf/conductor.h"
#include "core/bsdf/dielectric.h"
#include "core/bsdf/microfacet.h"
#include "core/params.h"

namespace caustica {

// A positive number or a named dielectric ("bk7", "water", ...).
float read_ior(const Params& p, const std::string& key, float fallback);
// int_ior / ext_ior: the relative index of the interior.
float read_eta(const Params& p, float int_default);
// distribution (ggx, beckmann; default ggx).
MicrofacetType read_distribution_type(const Params& p);
// distribution with alpha, or alpha_u and alpha_v, numbers.
MicrofacetDistribution read_distribution(const Params& p);
// The same, each alpha a number or a texture.
Roughness read_roughness(const Params& p);
// material (a named conductor) or eta and k; default Mitsuba's "none", a perfect mirror.
ConductorIor read_conductor(const Params& p);
// Mitsuba's specular_reflectance and specular_transmittance of a dielectric: colours or
// textures that scale its reflected and its transmitted light (default 1, which changes nothing).
DielectricTint read_dielectric_tint(const Params& p);
// Warns when a constant reflectance above 1 would create energy.
void check_albedo(const Params& p, const std::string& key, const ColorParam& c);

}  // namespace caustica
