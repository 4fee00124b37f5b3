// Octahedral direction encoding.
#include "photon/photon.h"

namespace caustica {

static float sign_not_zero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

uint16_t encode_direction(const Vec3& v) {
  const float l1 = std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
  if (!(l1 > 0.0f)) return 0x8080;
  float x = v.x / l1, y = v.y / l1;
  if (v.z < 0.0f) {
    const float ox = x;
    x = (1.0f - std::abs(y)) * sign_not_zero(ox);
    y = (1.0f - std::abs(ox)) * sign_not_zero(y);
  }
  auto q = [](float f) { return static_cast<uint16_t>(std::lround(std::clamp(f, -1.0f, 1.0f) * 127.5f + 127.5f)); };
  return static_cast<uint16_t>(q(x) | (q(y) << 8));
}

Vec3 decode_direction(uint16_t code) {
  const float x = (code & 0xff) / 127.5f - 1.0f, y = (code >> 8) / 127.5f - 1.0f;
  Vec3 v(x, y, 1.0f - std::abs(x) - std::abs(y));
  if (v.z < 0.0f) {
    const float ox = v.x;
    v.x = (1.0f - std::abs(v.y)) * sign_not_zero(ox);
    v.y = (1.0f - std::abs(ox)) * sign_not_zero(v.y);
  }
  return glm::normalize(v);
}

}  // namespace caustica
