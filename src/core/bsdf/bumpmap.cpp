// Bump mapping.
#include "core/bsdf/bumpmap.h"

namespace caustica {

Frame BumpMap::frame(const ShadingPoint& sp) const {
  Vec2 g(0.0f);
  if (height_) height_->gradient(sp.uv, g);
  g *= scale_;
  if (g == Vec2(0.0f) || !std::isfinite(g.x) || !std::isfinite(g.y)) return Frame();
  // The local frame's normal is +z: the tangents with their z replaced by the height's slopes.
  const Vec3 pu(sp.dpdu.x, sp.dpdu.y, g.x), pv(sp.dpdv.x, sp.dpdv.y, g.y);
  Vec3 n = glm::cross(pu, pv);
  const float len = glm::length(n);
  if (!(len > 0.0f) || !std::isfinite(len)) return Frame();
  n /= len;
  if (n.z < 0.0f) n = -n;
  if (!(n.z > 0.0f)) return Frame();
  return Frame(n, sp.dpdu);
}

std::unique_ptr<Bsdf> BumpMap::create(const Params& p) {
  const ColorParam height = p.texture("height", Color(0.0f));
  if (height.texture) {
    Vec2 g;
    if (!height.texture->gradient(Vec2(0.5f), g)) {
      p.fail("height", "a bump map's height texture must be a bitmap (this texture has no gradient)");
    }
  }
  const float scale = p.number("scale", 1.0f);
  const std::vector<const Bsdf*> nested = p.bsdfs("bsdf", false);
  return std::make_unique<BumpMap>(nested.front(), height.texture, scale);
}

}  // namespace caustica
