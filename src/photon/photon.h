// The photon record: 24 bytes (position, flux as three halves, octahedral directions).
#pragma once
#include <cstdint>
#include <glm/gtc/packing.hpp>
#include "core/math.h"

namespace caustica {

// Unit vector <-> two bytes, octahedral mapping (Cigolle et al. 2014): ~1 degree accuracy,
// ample for the side and normal tests of the radiance estimate.
uint16_t encode_direction(const Vec3& v);
Vec3 decode_direction(uint16_t code);

struct Photon {
  Vec3 position;
  uint16_t flux[3];   // half floats: 11 significant bits, no shared exponent between channels
  uint16_t incoming;  // direction towards where the photon came from (octahedral)
  uint16_t normal;    // surface normal on the side the photon arrived from (octahedral)
  uint16_t bounces = 0;  // diffuse and specular bounces before this one (0: first hit)

  static Photon make(const Vec3& p, const Color& flux, const Vec3& incoming, const Vec3& normal, int bounces) {
    Photon ph;
    ph.position = p;
    for (int c = 0; c < 3; ++c) ph.flux[c] = glm::packHalf1x16(flux[c]);
    ph.incoming = encode_direction(incoming);
    ph.normal = encode_direction(normal);
    ph.bounces = static_cast<uint16_t>(std::min(bounces, 65535));
    return ph;
  }
  Color power() const {
    return Color(glm::unpackHalf1x16(flux[0]), glm::unpackHalf1x16(flux[1]), glm::unpackHalf1x16(flux[2]));
  }
  Vec3 incoming_dir() const { return decode_direction(incoming); }
  Vec3 surface_normal() const { return decode_direction(normal); }
};
static_assert(sizeof(Photon) == 24, "photon record should stay compact");

}  // namespace caustica
