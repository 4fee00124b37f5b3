// Spectra of Mitsuba scenes turned into linear sRGB, the way Mitsuba 3's RGB variants do.
#pragma once
#include <utility>
#include <vector>
#include "core/math.h"

namespace caustica {

// What a spectrum means, which decides how it becomes RGB.
enum class SpectrumUse {
  Reflectance,  // weighted by the D65 illuminant, a flat 1 is white (1, 1, 1), clamped to [0, 1]
  Emission,     // an emitter's radiance: not weighted (Mitsuba 3: a flat 1 is (1.20, 0.95, 0.91))
  Unbounded,    // eta, k: not weighted, a flat c is (c, c, c)
};

// Linear sRGB of a spectrum given as (wavelength nm, value) pairs, linearly interpolated and zero
// outside the pairs' range.
Color spectrum_to_rgb(const std::vector<std::pair<double, double>>& samples, SpectrumUse use);

// The colour Mitsuba 3 gives a constant spectrum: c, except for an emitter, where it is c times
// the sRGB of a flat (equal-energy) spectrum.
Color constant_spectrum_to_rgb(double value, SpectrumUse use);

// Planck's law at `kelvin`, W m^-2 sr^-1 nm^-1, as linear sRGB (an emitter's spectrum).
Color blackbody_to_rgb(double kelvin);

// The CIE 1931 2-degree matching functions (the multi-lobe fit of Wyman, Sloan and Shirley 2013).
Vec3 cie_xyz(double lambda_nm);

}  // namespace caustica
