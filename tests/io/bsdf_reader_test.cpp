// Bsdf blocks with Mitsuba 3's names: what each type builds, the named indices, and the
// errors for bad values (each naming the file and the JSON pointer).
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "io/bsdf_reader.h"
#include "core/bsdf/conductor.h"
#include "core/bsdf/dielectric.h"
#include "core/bsdf/fresnel.h"
#include "photon/gather.h"

using namespace caustica;
using Catch::Matchers::Contains;

namespace {
std::unique_ptr<Bsdf> read(const std::string& text, std::vector<std::string>* warnings_out = nullptr) {
  const JsonReader r("m.json");
  std::vector<std::unique_ptr<Bsdf>> nested;
  std::vector<std::string> warnings;
  static std::vector<std::unique_ptr<Texture>> textures;
  const PluginContext ctx{r, ".", nested, textures, warnings};
  auto m = read_bsdf(ctx, nlohmann::json::parse(text), "/materials/x");
  if (warnings_out) *warnings_out = warnings;
  static std::vector<std::unique_ptr<Bsdf>> keep;  // nested materials outlive the call
  for (auto& n : nested) keep.push_back(std::move(n));
  return m;
}
const Vec3 kUp(0.0f, 0.0f, 1.0f);
}  // namespace

TEST_CASE("materials: each type has its lobe flags", "[core][bsdf_reader]" TIER_UNIT) {
  CHECK(read(R"({"type": "diffuse", "reflectance": 0.5})")->flags() == (kBsdfDiffuse | kBsdfReflection));
  CHECK(read(R"({"type": "diffuse", "albedo": [0.1, 0.2, 0.3]})")->albedo() == Color(0.1f, 0.2f, 0.3f));
  CHECK(read(R"({"type": "conductor", "material": "Au"})")->flags() == (kBsdfSpecular | kBsdfReflection));
  CHECK(read(R"({"type": "mirror"})")->is_specular());
  const auto rough = read(R"({"type": "roughconductor", "alpha_u": 0.1, "alpha_v": 0.4, "distribution": "beckmann"})");
  CHECK(rough->flags() == (kBsdfGlossy | kBsdfReflection));
  CHECK(rough->glossy_roughness() == Approx(0.1f));
  CHECK(read(R"({"type": "dielectric"})")->flags() == (kBsdfSpecular | kBsdfReflection | kBsdfTransmission));
  CHECK(read(R"({"type": "thindielectric"})")->is_specular());
  CHECK(read(R"({"type": "roughdielectric", "alpha": 0.3})")->flags() ==
        (kBsdfGlossy | kBsdfReflection | kBsdfTransmission));
  const auto phong = read(R"({"type": "phong", "diffuse_reflectance": 0.1, "specular_reflectance": 0.7, "exponent": 90})");
  CHECK(phong->flags() == (kBsdfDiffuse | kBsdfGlossy | kBsdfReflection));
  CHECK(phong->glossy_roughness() == Approx(std::sqrt(2.0 / 92.0)));
  const auto two = read(R"({"type": "twosided", "bsdf": [{"type": "diffuse"}, {"type": "conductor"}]})");
  CHECK(two->flags() == (kBsdfDiffuse | kBsdfReflection | kBsdfSpecular));
}

TEST_CASE("materials: photon mapping's gather rule follows the glossy threshold", "[core][bsdf_reader]" TIER_UNIT) {
  CHECK(is_gather_surface(*read(R"({"type": "diffuse"})"), 0.3f));
  CHECK_FALSE(is_gather_surface(*read(R"({"type": "conductor"})"), 0.0f));
  const auto rough = read(R"({"type": "roughconductor", "alpha": 0.2})");
  CHECK_FALSE(is_gather_surface(*rough, 0.3f));
  CHECK(is_gather_surface(*rough, 0.2f));
  CHECK(is_gather_surface(*read(R"({"type": "phong", "exponent": 10000})"), 0.3f));  // has a diffuse lobe
  // Rough glass is traced through at any roughness: its transmitted light comes from behind.
  CHECK_FALSE(is_gather_surface(*read(R"({"type": "roughdielectric", "alpha": 0.8})"), 0.3f));
}

TEST_CASE("materials: named indices of refraction", "[core][bsdf_reader]" TIER_UNIT) {
  // Two dielectrics whose eta differ only by name versus number reflect the same.
  const auto named = read(R"({"type": "dielectric", "int_ior": "diamond", "ext_ior": "vacuum"})");
  const auto numeric = read(R"({"type": "dielectric", "int_ior": 2.419, "ext_ior": 1.0})");
  const Vec3 wo = glm::normalize(Vec3(0.3f, 0.2f, 0.8f));
  BsdfSample a[2], b[2];
  REQUIRE(named->specular_lobes(wo, a) == 2);
  REQUIRE(numeric->specular_lobes(wo, b) == 2);
  CHECK(a[0].weight.x == Approx(b[0].weight.x));
  CHECK(a[0].weight.x == Approx(fresnel_dielectric(wo.z, 2.419f)));
  // Gold at normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2) per channel, warm (red > blue).
  const auto gold = read(R"({"type": "conductor", "material": "Au"})");
  BsdfSample g;
  REQUIRE(gold->specular_lobes(kUp, &g) == 1);
  const double n = 0.143036, k = 3.983;  // src/core/bsdf/conductor_table.inc
  CHECK(g.weight.x == Approx(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k)).epsilon(1e-4));
  CHECK(g.weight.x > g.weight.z + 0.4f);
  // eta and k given directly equal the named metal.
  const auto explicit_gold =
      read(R"({"type": "conductor", "eta": [0.143036, 0.375307, 1.44205], "k": [3.983, 2.38556, 1.60336]})");
  BsdfSample e;
  REQUIRE(explicit_gold->specular_lobes(kUp, &e) == 1);
  CHECK(e.weight.y == Approx(g.weight.y));
}

TEST_CASE("materials: bad values are errors naming the file and the key", "[core][bsdf_reader]" TIER_UNIT) {
  CHECK_THROWS_WITH(read(R"({"type": "conductor", "material": "Unobtainium"})"),
                    Contains("m.json: /materials/x/material") && Contains("unknown conductor \"Unobtainium\"") &&
                        Contains("Au") && Contains("Ni"));
  CHECK_THROWS_WITH(read(R"({"type": "dielectric", "int_ior": "glas"})"),
                    Contains("/materials/x/int_ior") && Contains("unknown index of refraction") && Contains("bk7") &&
                        Contains("water"));
  CHECK_THROWS_WITH(read(R"({"type": "roughconductor", "alpha": -0.1})"), Contains("/materials/x/alpha"));
  CHECK_THROWS_WITH(read(R"({"type": "roughconductor", "alpha": 0.1, "alpha_u": 0.2, "alpha_v": 0.2})"),
                    Contains("either alpha or alpha_u and alpha_v"));
  CHECK_THROWS_WITH(read(R"({"type": "roughconductor", "alpha_u": 0.2})"), Contains("alpha_u and alpha_v go together"));
  CHECK_THROWS_WITH(read(R"({"type": "roughdielectric", "distribution": "phong"})"),
                    Contains("/materials/x/distribution") && Contains("ggx, beckmann"));
  CHECK_THROWS_WITH(read(R"({"type": "conductor", "eta": 0.2})"), Contains("eta and k go together"));
  CHECK_THROWS_WITH(read(R"({"type": "dielectric", "int_ior": -1.5})"), Contains("must be positive"));
  CHECK_THROWS_WITH(read(R"({"type": "diffuse", "reflectanse": 0.5})"),
                    Contains("/materials/x/reflectanse") && Contains("reflectance"));
  CHECK_THROWS_WITH(read(R"({"type": "plasticc"})"),
                    Contains("unknown material type \"plasticc\"") && Contains("roughconductor"));
  // "emission" (the area light's radiance) only on the outermost block, and not on a mask.
  CHECK_THROWS_WITH(read(R"({"type": "twosided", "bsdf": [{"type": "diffuse", "emission": 1}]})"),
                    Contains("/materials/x/bsdf/0/emission") && Contains("emission belongs on the outermost material"));
  CHECK_THROWS_WITH(read(R"({"type": "mask", "emission": 1, "bsdf": {"type": "diffuse"}})"),
                    Contains("/materials/x/emission") && Contains("a mask material cannot emit light"));
  CHECK_THROWS_WITH(read(R"({"type": "mask", "bsdf": {"type": "diffuse", "emission": 1}})"),
                    Contains("/materials/x/bsdf/emission") && Contains("outermost"));
  CHECK_NOTHROW(read(R"({"type": "glass", "emission": [1, 2, 3]})"));
  std::vector<std::string> warnings;
  read(R"({"type": "phong", "diffuse_reflectance": 0.6, "specular_reflectance": 0.6})", &warnings);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Contains("creates energy"));
}
