// Photon mapping's rules for surfaces. Gather surfaces, where photons are stored and the eye path
// stops to gather: a diffuse lobe, or a glossy reflection lobe at least `glossy_threshold` rough
// (microfacet alpha). Glossy transmission (rough glass) is always traced through: a density
// estimate only sees photons on the viewer's side and would miss the light coming through.
// Of the surfaces traced through, caustic surfaces (a delta lobe, or glossy lobes smoother than
// `caustic_threshold`) carry the caustic map's photons; the rougher ones are soft: light reaching
// a gather point through them is the final gather's (shadow rays at the soft vertex, MIS), for
// which a soft glossy reflection of an environment or a large light is cheap and clean, and the
// caustic map would be neither.
#pragma once
#include "core/bsdf/bsdf.h"

namespace caustica {

inline bool is_gather_surface(const Bsdf& m, float glossy_threshold) {
  const uint32_t f = m.flags();
  if ((f & kBsdfDiffuse) != 0) return true;
  return (f & kBsdfGlossy) != 0 && (f & kBsdfTransmission) == 0 && m.glossy_roughness() >= glossy_threshold;
}

// For a surface that is not a gather surface: does it carry caustic photons?
inline bool is_caustic_surface(const Bsdf& m, float caustic_threshold) {
  return m.has(kBsdfSpecular) || m.glossy_roughness() < caustic_threshold;
}

// The delta lobes of a gather surface (plastic's coat; glass blended with a diffuse BSDF), which
// no photon estimate holds: the direction along which a caustic photon or a gather ray passes
// on. One listed lobe is followed with its weight. Otherwise (two lobes, or more than
// specular_lobes can list) one BSDF sample is, when it is a delta one: its weight is the lobe's
// over its chance, so its mean is the delta lobes' part and no more. False: none (the numbers
// are drawn from `uniform` only then).
template <class Uniform>
bool delta_continuation(const Bsdf& m, const Vec3& wo, const ShadingPoint& sp, Uniform&& uniform, BsdfSample& out) {
  if (!m.has(kBsdfSpecular)) return false;
  BsdfSample listed[2];
  if (m.specular_lobes(wo, listed, sp) == 1) {
    out = listed[0];
    return true;
  }
  const float u_lobe = uniform();
  const float u0 = uniform(), u1 = uniform();
  return m.sample(wo, Vec2(u0, u1), u_lobe, out, sp) && out.delta;
}

}  // namespace caustica
