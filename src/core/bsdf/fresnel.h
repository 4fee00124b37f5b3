// Fresnel reflectance of dielectric and conducting boundaries, and Snell's law.
#pragma once
#include "core/math.h"

namespace caustica {

enum class FresnelModel { Exact, Schlick };

// Unpolarised Fresnel reflectance of a dielectric boundary. cos_i > 0 is measured on the
// incident side; eta = n_transmitted / n_incident. Returns 1 under total internal reflection.
float fresnel_dielectric(float cos_i, float eta);
float fresnel_schlick(float cos_i, float eta);

// Unpolarised reflectance of a conductor with complex index eta + i k (relative to the outside
// medium), per RGB channel, from the amplitude coefficients r_s and r_p in complex arithmetic.
Color fresnel_conductor(float cos_i, const Color& eta, const Color& k);

// Refraction of wi (pointing away from the surface, on the side of n) through a boundary with
// eta = n_transmitted / n_incident. False under total internal reflection.
bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3& wt);

}  // namespace caustica
