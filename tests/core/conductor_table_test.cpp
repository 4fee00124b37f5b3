// The named conductors against their spectra: tests/data/conductor_spectra.txt holds mitsuba-data's
// ior/ tables resampled (scripts/make_conductor_fixture.py); this test converts them to RGB on its
// own (a midpoint rule at 4000 wavelengths, not the generator's 1000 end-to-end points) and
// compares the Fresnel reflectance at normal incidence with what the shipped table gives.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#include "core/bsdf/fresnel.h"
#include "core/bsdf/ior.h"

using namespace caustica;

namespace {

using Spectrum = std::vector<std::pair<double, double>>;

std::vector<std::vector<double>> read_cie() {
  std::ifstream in(std::string(CAUSTICA_SOURCE_DIR) + "/scripts/data/cie1931_2deg_5nm.txt");
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::vector<double> row;
    for (double v; s >> v;) row.push_back(v);
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

double interpolate(const Spectrum& s, double l) {
  if (s.empty() || l < s.front().first || l > s.back().first) return 0.0;
  for (size_t i = 1; i < s.size(); ++i) {
    if (l <= s[i].first) {
      const double t = (l - s[i - 1].first) / (s[i].first - s[i - 1].first);
      return s[i - 1].second + t * (s[i].second - s[i - 1].second);
    }
  }
  return s.back().second;
}

// Linear sRGB of a spectrum, unweighted and unnormalised but for CIE Y's 1 / 106.75 (what
// Mitsuba 3's RGB variants do with a named material's eta and k).
glm::dvec3 to_rgb(const Spectrum& s, const std::vector<std::vector<double>>& cie) {
  constexpr int kSteps = 4000;
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < kSteps; ++i) {
    const double l = 360.0 + 470.0 * (i + 0.5) / kSteps;
    const double t = (l - 360.0) / 5.0;
    const size_t j = std::min<size_t>(size_t(t), 93);
    const double w = t - double(j);
    for (int c = 0; c < 3; ++c) xyz[c] += ((1 - w) * cie[c][j] + w * cie[c][j + 1]) * interpolate(s, l);
  }
  xyz *= 470.0 / kSteps / 106.7502593994140625;
  const glm::dvec3 rgb(3.240479 * xyz.x - 1.537150 * xyz.y - 0.498535 * xyz.z,
                       -0.969256 * xyz.x + 1.875991 * xyz.y + 0.041556 * xyz.z,
                       0.055648 * xyz.x - 0.204043 * xyz.y + 1.057311 * xyz.z);
  return glm::max(rgb, glm::dvec3(0.0));
}

double r0(double n, double k) { return ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k); }

}  // namespace

TEST_CASE("Named conductors: every table's Fresnel at normal incidence within 1 % of its spectra", "[core][bsdf]" TIER_UNIT) {
  const auto cie = read_cie();
  REQUIRE(cie.size() == 3);
  REQUIRE(cie[0].size() == 95);
  std::ifstream in(std::string(CAUSTICA_SOURCE_DIR) + "/tests/data/conductor_spectra.txt");
  REQUIRE(in);
  std::map<std::string, std::map<std::string, Spectrum>> spectra;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string name, part, pair;
    s >> name >> part;
    while (s >> pair) {
      const size_t colon = pair.find(':');
      spectra[name][part].emplace_back(std::stod(pair.substr(0, colon)), std::stod(pair.substr(colon + 1)));
    }
  }
  REQUIRE(spectra.size() >= 70);
  for (const auto& [name, parts] : spectra) {
    INFO(name);
    ConductorIor ior;
    REQUIRE(lookup_conductor(name, ior));
    const glm::dvec3 eta = to_rgb(parts.at("eta"), cie), k = to_rgb(parts.at("k"), cie);
    const Color f = fresnel_conductor(1.0f, ior.eta, ior.k);
    for (int c = 0; c < 3; ++c) {
      INFO("channel " << c << ": eta " << ior.eta[c] << " (spectra: " << eta[c] << "), k " << ior.k[c] << " (" << k[c] << ")");
      CHECK(std::isfinite(f[c]));
      if (eta[c] < 0.05) {
        // A table that ends inside the visible range (AlSb at 590 nm) leaves a channel whose
        // eta is the difference of nearly equal terms, set to 0 where negative: both near 0.
        CHECK(ior.eta[c] < 0.05f);
        continue;
      }
      CHECK(f[c] == Approx(r0(eta[c], k[c])).epsilon(0.01));
    }
  }
}

TEST_CASE("Named conductors: every name of Mitsuba's documentation is known", "[core][bsdf]" TIER_UNIT) {
  for (const char* name : {"a-C", "Ag", "Al", "AlAs", "AlSb", "Au", "Be", "Cr", "CsI", "Cu", "Cu2O", "CuO", "d-C",
                           "Hg", "HgTe", "Ir", "K", "Li", "MgO", "Mo", "Na_palik", "Nb", "Ni_palik", "Rh", "Se",
                           "SiC", "SnTe", "Ta", "Te", "ThF4", "TiC", "TiN", "TiO2", "VC", "V", "VN", "W", "none",
                           "Ni", "Cu_palik", "TiO2-e"}) {
    INFO(name);
    ConductorIor ior;
    CHECK(lookup_conductor(name, ior));
    CHECK(known_conductors().find(name) != std::string::npos);
    for (int i = 0; i <= 20; ++i) {
      const Color f = ior.reflectance(i / 20.0f);
      for (int c = 0; c < 3; ++c) {
        CHECK(std::isfinite(f[c]));
        CHECK(f[c] >= 0.0f);
        CHECK(f[c] <= 1.0f + 1e-5f);
      }
    }
  }
}
