// Fresnel (exact and Schlick), glass and mirror sampling against double-precision references
// and textbook values.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include "core/bsdf/conductor.h"
#include "core/bsdf/dielectric.h"
#include "core/bsdf/diffuse.h"
#include "core/rng.h"
#include "core/sampling.h"

using namespace caustica;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Fresnel's equations in their angle form (Born & Wolf 1.5.3), a different route from the
// renderer's cosine form: Rs = sin^2(i - t) / sin^2(i + t), Rp = tan^2(i - t) / tan^2(i + t).
struct FresnelRef {
  double rs, rp;
  double average() const { return 0.5 * (rs + rp); }
};
FresnelRef fresnel_reference(double theta_i, double eta) {
  const double sin_t = std::sin(theta_i) / eta;
  if (sin_t >= 1.0) return {1.0, 1.0};
  if (theta_i == 0.0) {
    const double r0 = (eta - 1.0) / (eta + 1.0);
    return {r0 * r0, r0 * r0};
  }
  const double theta_t = std::asin(sin_t);
  const double s = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
  const double t = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
  return {s * s, t * t};
}

Vec3 direction(double theta, double phi, bool below = false) {
  const Vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
  return below ? Vec3(w.x, w.y, -w.z) : w;
}
}  // namespace

TEST_CASE("fresnel_dielectric: normal incidence and 45 degrees for glass", "[core][material]" TIER_UNIT) {
  CHECK(fresnel_dielectric(1.0f, 1.5f) == Approx(0.04).margin(1e-6));
  CHECK(fresnel_dielectric(1.0f, 1.0f / 1.5f) == Approx(0.04).margin(1e-6));  // same from inside

  const FresnelRef at45 = fresnel_reference(45 * kDeg, 1.5);
  // Textbook values for n = 1.5 at 45 degrees: Rs = 0.0920, Rp = 0.0085, average 0.0503.
  CHECK(at45.rs == Approx(0.09204).margin(1e-4));
  CHECK(at45.rp == Approx(0.00847).margin(1e-4));
  CHECK(at45.average() == Approx(0.05025).margin(1e-4));
  const float f45 = fresnel_dielectric(float(std::cos(45 * kDeg)), 1.5f);
  CHECK(f45 == Approx(at45.average()).margin(1e-6));
  CHECK(f45 == Approx(0.05025).margin(1e-3));
}

TEST_CASE("fresnel_dielectric matches the angle form at all angles, both ways", "[core][material]" TIER_UNIT) {
  for (double eta : {1.33, 1.5, 2.4}) {
    for (double deg = 0; deg < 90; deg += 0.5) {
      INFO("eta " << eta << ", " << deg << " degrees");
      const double theta = deg * kDeg;
      const float cos_i = float(std::cos(theta));
      REQUIRE(fresnel_dielectric(cos_i, float(eta)) == Approx(fresnel_reference(theta, eta).average()).margin(2e-6));
      // From the dense side, below the critical angle.
      if (std::sin(theta) * eta < 0.999) {
        REQUIRE(fresnel_dielectric(cos_i, float(1.0 / eta)) ==
                Approx(fresnel_reference(theta, 1.0 / eta).average()).margin(1e-5));
        // Reciprocity: the same reflectance seen from the transmitted side.
        const double cos_t = std::sqrt(1.0 - std::pow(std::sin(theta) / eta, 2));
        REQUIRE(fresnel_dielectric(float(cos_t), float(1.0 / eta)) == Approx(fresnel_dielectric(cos_i, float(eta))).margin(1e-5));
      }
    }
  }
  CHECK(fresnel_dielectric(0.0f, 1.5f) == Approx(1.0f));  // grazing
}

TEST_CASE("fresnel_dielectric: total internal reflection beyond the critical angle", "[core][material]" TIER_UNIT) {
  const float eta = 1.0f / 1.5f;
  const double critical = std::asin(1.0 / 1.5) / kDeg;  // 41.81 degrees
  REQUIRE(critical == Approx(41.81).margin(0.005));
  for (double deg = 41.82; deg < 90.0; deg += 0.25) {
    INFO(deg << " degrees");
    REQUIRE(fresnel_dielectric(float(std::cos(deg * kDeg)), eta) == 1.0f);
  }
  const float just_below = fresnel_dielectric(float(std::cos(41.8 * kDeg)), eta);
  CHECK(just_below < 1.0f);
  CHECK(just_below == Approx(fresnel_reference(41.8 * kDeg, 1.0 / 1.5).average()).margin(1e-3));
  CHECK(fresnel_dielectric(float(std::cos(30 * kDeg)), eta) < 0.1f);
}

TEST_CASE("fresnel_schlick: R0 at normal incidence, close to exact at 30 degrees", "[core][material]" TIER_UNIT) {
  CHECK(fresnel_schlick(1.0f, 1.5f) == Approx(0.04).margin(1e-6));
  const float c30 = float(std::cos(30 * kDeg));
  CHECK(std::abs(fresnel_schlick(c30, 1.5f) - fresnel_reference(30 * kDeg, 1.5).average()) < 0.01);
  CHECK(fresnel_schlick(0.0f, 1.5f) == Approx(1.0f));
  // From inside, Schlick uses the angle on the thin side: equal to the outside value there.
  for (double deg : {10.0, 25.0, 40.0}) {
    const double sin_t = std::sin(deg * kDeg) * 1.5;  // transmitted angle outside
    const float cos_t = float(std::sqrt(1.0 - sin_t * sin_t));
    CHECK(fresnel_schlick(float(std::cos(deg * kDeg)), 1.0f / 1.5f) == Approx(fresnel_schlick(cos_t, 1.5f)).margin(1e-5));
  }
  CHECK(fresnel_schlick(float(std::cos(45 * kDeg)), 1.0f / 1.5f) == 1.0f);  // total internal reflection
}

TEST_CASE("Dielectric::sample: reflection fraction is the Fresnel reflectance, refraction obeys Snell", "[core][material]" TIER_UNIT) {
  const float ior = 1.5f;
  const int n = 200000;
  for (const FresnelModel model : {FresnelModel::Exact, FresnelModel::Schlick}) {
    const Dielectric glass(ior, model);
    CHECK(glass.is_specular());
    CHECK(glass.flags() == (kBsdfSpecular | kBsdfReflection | kBsdfTransmission));
    for (const bool inside : {false, true}) {
      for (const double deg : {0.0, 20.0, 45.0, 70.0, 85.0}) {
        const Vec3 wo = direction(deg * kDeg, 0.7, inside);
        const float expected_f =
            model == FresnelModel::Exact ? float(fresnel_reference(deg * kDeg, inside ? 1.0 / ior : ior).average())
                                         : fresnel_schlick(float(std::cos(deg * kDeg)), inside ? 1.0f / ior : ior);
        INFO((model == FresnelModel::Exact ? "exact" : "schlick") << (inside ? ", inside" : ", outside") << ", " << deg << " degrees");
        const float f = glass.reflectance(wo);
        CHECK(f == Approx(expected_f).margin(1e-5));
        const double n1 = inside ? ior : 1.0, n2 = inside ? 1.0 : ior;

        Rng rng(uint64_t(deg * 10) + inside);
        int reflected = 0, bad_reflection = 0, bad_snell = 0, same_side = 0, bad_plane = 0, bad_weight = 0, failed = 0;
        for (int k = 0; k < n; ++k) {
          BsdfSample s;
          if (!glass.sample(wo, Vec2(rng.next_float(), rng.next_float()), rng.next_float(), s)) {
            ++failed;
            continue;
          }
          if (!s.delta || s.pdf != 0.0f || s.weight != Color(1.0f)) ++bad_weight;
          if (s.wi.z * wo.z > 0) {
            ++reflected;
            if (glm::length(s.wi - reflect_local(wo)) > 1e-6f) ++bad_reflection;
          } else {
            if (s.wi.z == 0) ++same_side;
            // n1 sin(theta_1) = n2 sin(theta_2), in the plane of incidence, on the other side.
            const double sin_o = std::hypot(wo.x, wo.y), sin_t = std::hypot(s.wi.x, s.wi.y);
            if (std::abs(n1 * sin_o - n2 * sin_t) > 1e-5) ++bad_snell;
            if (std::abs(glm::length(s.wi) - 1.0f) > 1e-5f) ++bad_snell;
            if (deg > 0 && (std::abs(wo.x * s.wi.y - wo.y * s.wi.x) > 1e-5f || wo.x * s.wi.x + wo.y * s.wi.y > 0)) ++bad_plane;
          }
        }
        CHECK(failed == 0);
        CHECK(bad_weight == 0);
        CHECK(bad_reflection == 0);
        CHECK(bad_snell == 0);
        CHECK(same_side == 0);
        CHECK(bad_plane == 0);
        // Binomial: the fraction reflected is F within 5 standard deviations.
        const double sigma = std::sqrt(std::max(1e-12, double(f) * (1.0 - f) / n));
        CHECK(double(reflected) / n == Approx(f).margin(5.0 * sigma + 1e-6));

        // Energy: the refracted direction seen from its side has the same reflectance (R + T = 1 both ways).
        Vec3 wt;
        if (glass.refract(wo, wt)) {
          CHECK(wt.z * wo.z < 0);
          CHECK(glass.reflectance(wt) == Approx(f).margin(1e-5));
          CHECK(1.0f - glass.reflectance(wo) == Approx(1.0 - expected_f).margin(1e-5));
        } else {
          CHECK(f == 1.0f);
          CHECK(reflected == n);
        }
      }
    }
  }
}

TEST_CASE("Dielectric: total internal reflection always reflects", "[core][material]" TIER_UNIT) {
  const Dielectric glass(1.5f, FresnelModel::Exact);
  const Vec3 wo = direction(60 * kDeg, 1.3, /*below=*/true);
  Vec3 wt;
  CHECK_FALSE(glass.refract(wo, wt));
  CHECK(glass.reflectance(wo) == 1.0f);
  for (float u : {0.0f, 0.5f, 0.999999f}) {
    BsdfSample s;
    REQUIRE(glass.sample(wo, Vec2(0.5f), u, s));
    CHECK(glm::length(s.wi - reflect_local(wo)) < 1e-6f);
  }
  BsdfSample s;
  CHECK_FALSE(glass.sample(Vec3(1, 0, 0), Vec2(0.5f), 0.5f, s));
  CHECK(glass.albedo() == Color(1.0f));
  CHECK(is_black(glass.eval(Vec3(0, 0, 1), Vec3(0, 0, 1))));
}

TEST_CASE("Conductor without an index (mirror) reflects about the normal with weight = reflectance", "[core][material]" TIER_UNIT) {
  const Color refl(0.9f, 0.5f, 0.1f);
  const Conductor mirror(ConductorIor{}, refl);
  CHECK(mirror.is_specular());
  CHECK(mirror.albedo() == refl);
  Rng rng(9);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 normal = sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
    const Frame frame(normal);
    const Vec3 wo_world = sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
    const Vec3 wo = frame.to_local(wo_world);
    if (std::abs(wo.z) < 1e-3f) continue;
    BsdfSample s;
    REQUIRE(mirror.sample(wo, Vec2(rng.next_float(), rng.next_float()), rng.next_float(), s));
    const Vec3 expected = 2.0f * glm::dot(normal, wo_world) * normal - wo_world;
    REQUIRE(glm::length(frame.to_world(s.wi) - expected) < 1e-5f);
    REQUIRE(s.weight == refl);
    REQUIRE(s.delta);
    REQUIRE(s.pdf == 0.0f);
    REQUIRE(is_black(mirror.eval(wo, s.wi)));
    REQUIRE(mirror.pdf(wo, s.wi) == 0.0f);
  }
  BsdfSample s;
  CHECK_FALSE(mirror.sample(Vec3(0, 1, 0), Vec2(0.5f), 0.5f, s));
}

