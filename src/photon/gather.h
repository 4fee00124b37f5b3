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

}  // namespace caustica
