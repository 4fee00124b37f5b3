// Photon mapping's rule for where photons are stored and where the eye path stops to gather: a
// diffuse lobe, or a glossy reflection lobe at least `glossy_threshold` rough (microfacet
// alpha). Glossy transmission (rough glass) is always traced through: a density estimate only
// sees photons on the viewer's side and would miss the light coming through.
#pragma once
#include "core/bsdf/bsdf.h"

namespace caustica {

inline bool is_gather_surface(const Bsdf& m, float glossy_threshold) {
  const uint32_t f = m.flags();
  if ((f & kBsdfDiffuse) != 0) return true;
  return (f & kBsdfGlossy) != 0 && (f & kBsdfTransmission) == 0 && m.glossy_roughness() >= glossy_threshold;
}

}  // namespace caustica
