// Spectrum to linear sRGB: integrate against the CIE 1931 matching functions, then XYZ -> sRGB.
//
// Mitsuba 3 integrates 1000 points over 360-830 nm against its tabulated CIE curves and the D65
// table. We use the analytic fit of the CIE curves by Wyman, Sloan and Shirley ("Simple Analytic
// Approximations to the CIE XYZ Color Matching Functions", JCGT 2013; under 1 % of the peak from
// the tables) and, for D65, a 6504 K Planck spectrum; reflectances are then scaled so that a flat
// spectrum of 1 is white exactly, which Mitsuba's tables give too. Differences from Mitsuba are
// about a per cent for smooth spectra.
#include "io/mitsuba/spectrum.h"
#include <algorithm>
#include <cmath>

namespace caustica {
namespace {

constexpr double kMin = 360.0, kMax = 830.0;
constexpr int kSteps = 1000;
constexpr double kCieYNormalization = 1.0 / 106.7502593994140625;

double lobe(double x, double mu, double s1, double s2) {
  const double t = (x - mu) / (x < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}

Color xyz_to_srgb(const glm::dvec3& c) {
  return Color(float(3.240479 * c.x - 1.537150 * c.y - 0.498535 * c.z),
               float(-0.969256 * c.x + 1.875991 * c.y + 0.041556 * c.z),
               float(0.055648 * c.x - 0.204043 * c.y + 1.057311 * c.z));
}

double planck(double lambda_nm, double kelvin) {
  constexpr double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23;
  const double l = lambda_nm * 1e-9;
  return 2.0 * h * c * c / (std::pow(l, 5.0) * (std::exp(h * c / (l * k * kelvin)) - 1.0)) * 1e-9;
}

// D65 stand-in: 6504 K, relative, 100 at 560 nm.
double d65(double lambda_nm) { return 100.0 * planck(lambda_nm, 6504.0) / planck(560.0, 6504.0); }

template <class F>
glm::dvec3 integrate_xyz(F value, bool illuminant) {
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < kSteps; ++i) {
    const double l = kMin + (kMax - kMin) * (i + 0.5) / kSteps;
    const double w = illuminant ? 1.0 : d65(l) / 98.99741751876255;
    xyz += glm::dvec3(cie_xyz(l)) * value(l) * w;
  }
  return xyz * ((kMax - kMin) / kSteps) * kCieYNormalization;
}

}  // namespace

Vec3 cie_xyz(double l) {
  const double x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) - 0.065 * lobe(l, 501.1, 20.4, 26.2);
  const double y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
  const double z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
  return Vec3(float(x), float(y), float(z));
}

Color spectrum_to_rgb(const std::vector<std::pair<double, double>>& samples, SpectrumUse use) {
  const bool illuminant = use != SpectrumUse::Reflectance;
  if (samples.empty()) return Color(0.0f);
  auto value = [&](double l) {
    if (l < samples.front().first || l > samples.back().first) return 0.0;
    const auto hi = std::lower_bound(samples.begin(), samples.end(), l,
                                     [](const std::pair<double, double>& s, double x) { return s.first < x; });
    if (hi == samples.begin()) return hi->second;
    const auto lo = hi - 1;
    const double t = (l - lo->first) / (hi->first - lo->first);
    return lo->second + t * (hi->second - lo->second);
  };
  Color rgb = xyz_to_srgb(integrate_xyz(value, illuminant));
  if (use != SpectrumUse::Emission) {
    const Color flat = xyz_to_srgb(integrate_xyz([](double) { return 1.0; }, illuminant));
    rgb /= flat;
    if (use == SpectrumUse::Reflectance) rgb = glm::min(rgb, Color(1.0f));
  }
  return glm::max(rgb, Color(0.0f));
}

Color constant_spectrum_to_rgb(double value, SpectrumUse use) {
  if (use != SpectrumUse::Emission) return Color(float(value));
  return float(value) * xyz_to_srgb(integrate_xyz([](double) { return 1.0; }, true));
}

Color blackbody_to_rgb(double kelvin) {
  return glm::max(xyz_to_srgb(integrate_xyz([&](double l) { return planck(l, kelvin); }, true)), Color(0.0f));
}

}  // namespace caustica
