// Tables of indices of refraction.
#include "core/bsdf/ior.h"

namespace caustica {
namespace {

struct NamedIor {
  const char* name;
  float ior;
};
// Mitsuba 3's table of dielectric indices (its `dielectric` plugin documentation), at 589 nm.
constexpr NamedIor kDielectrics[] = {
    {"vacuum", 1.0f},         {"helium", 1.00004f},         {"hydrogen", 1.00013f},  {"air", 1.00028f},
    {"carbon dioxide", 1.00045f}, {"water", 1.3330f},       {"acetone", 1.36f},      {"ethanol", 1.361f},
    {"carbon tetrachloride", 1.461f}, {"glycerol", 1.4729f}, {"benzene", 1.501f},    {"silicone oil", 1.52045f},
    {"bromine", 1.661f},      {"water ice", 1.31f},         {"fused quartz", 1.458f}, {"pyrex", 1.470f},
    {"acrylic glass", 1.49f}, {"polypropylene", 1.49f},     {"bk7", 1.5046f},        {"sodium chloride", 1.544f},
    {"amber", 1.55f},         {"pet", 1.5750f},             {"diamond", 2.419f},
};

struct NamedMetal {
  const char* name;
  Color eta, k;
};
// Complex indices at 650, 550 and 450 nm (R, G, B), as tabulated by refractiveindex.info from:
// Au, Ag, Cu: P. B. Johnson and R. W. Christy, Phys. Rev. B 6, 4370 (1972);
// Cr: P. B. Johnson and R. W. Christy, Phys. Rev. B 9, 5056 (1974);
// Al: A. D. Rakic, Appl. Opt. 34, 4755 (1995);
// Ni: A. D. Rakic et al., Appl. Opt. 37, 5271 (1998), their Lorentz-Drude fit evaluated at the
// three wavelengths (Mitsuba's "Ni_palik" uses Palik's handbook; the two agree within ~5 %).
const NamedMetal kMetals[] = {
    {"Au", {0.18299f, 0.42108f, 1.3734f}, {3.4242f, 2.3459f, 1.7704f}},
    {"Ag", {0.15943f, 0.14512f, 0.13547f}, {3.9291f, 3.1900f, 2.3808f}},
    {"Cu", {0.27105f, 0.67693f, 1.3164f}, {3.6092f, 2.6248f, 2.2921f}},
    {"Al", {1.3456f, 0.96521f, 0.61722f}, {7.4746f, 6.3995f, 5.3031f}},
    {"Cr", {3.1071f, 3.1812f, 2.3230f}, {3.3314f, 3.3291f, 3.1350f}},
    {"Ni", {2.0587f, 1.8145f, 1.6493f}, {3.7635f, 3.2587f, 2.6706f}},
    {"Ni_palik", {2.0587f, 1.8145f, 1.6493f}, {3.7635f, 3.2587f, 2.6706f}},
};

}  // namespace

bool lookup_dielectric_ior(const std::string& name, float& ior) {
  for (const NamedIor& d : kDielectrics) {
    if (name == d.name) {
      ior = d.ior;
      return true;
    }
  }
  return false;
}

std::string known_dielectrics() {
  std::string s;
  for (const NamedIor& d : kDielectrics) s += (s.empty() ? "" : ", ") + std::string(d.name);
  return s;
}

bool lookup_conductor(const std::string& name, ConductorIor& ior) {
  if (name == "none") {
    ior = ConductorIor{};
    return true;
  }
  for (const NamedMetal& m : kMetals) {
    if (name == m.name) {
      ior = ConductorIor{m.eta, m.k};
      return true;
    }
  }
  return false;
}

std::string known_conductors() {
  std::string s = "none";
  for (const NamedMetal& m : kMetals) s += ", " + std::string(m.name);
  return s;
}

}  // namespace caustica
