// The integrator registry drives the command line: every settings key is a flag, and a flag
// applies to exactly the integrators whose row lists its key.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include "app/scene_setup.h"
#include "support/errors.h"
#include "support/temp_dir.h"

using namespace caustica;

TEST_CASE("integrators: a flag applies exactly to the integrators whose registry row lists its key", "[app][registry]" TIER_UNIT) {
  SceneOptions options;
  options.scene = std::string(CAUSTICA_SOURCE_DIR) + "/tests/data/tiny.json";
  options.quiet = true;
  LoadedScene loaded = load_scene_with(options);
  size_t accepted = 0, refused = 0;
  for (const IntegratorPlugin& row : integrator_plugins()) {
    for (const IntegratorSetting& s : integrator_settings()) {
      INFO(row.name << " " << s.key);
      const nlohmann::json value = s.kind == SettingKind::Boolean ? nlohmann::json(true)
                                   : s.kind == SettingKind::Real  ? nlohmann::json(0.5)
                                                                  : nlohmann::json(1);
      options.integrator_overrides = {{s.key, value}};
      const std::string error = test::error_of([&] { integrator_for(loaded, row.name, options); });
      const bool listed = row.reads(s.key);
      if (listed) {
        CHECK(error.empty());
        ++accepted;
      } else {
        std::string flag = "--" + std::string(s.key);
        std::replace(flag.begin(), flag.end(), '_', '-');
        CHECK(error == flag + " does not apply to integrator \"" + row.name + "\"");
        ++refused;
      }
    }
  }
  CHECK(accepted >= 30);
  CHECK(refused >= 30);
  // Every key a row lists is a known setting with a flag.
  for (const IntegratorPlugin& row : integrator_plugins()) {
    for (const char* key : row.keys) {
      INFO(row.name << " " << key);
      CHECK(find_integrator_setting(key) != nullptr);
    }
  }
}

TEST_CASE("integrators: the docs name every registered integrator", "[app][registry]" TIER_UNIT) {
  const std::string format = test::read_text(std::string(CAUSTICA_SOURCE_DIR) + "/docs/scene-format.md");
  for (const IntegratorPlugin& row : integrator_plugins()) {
    INFO(row.name);
    CHECK(format.find("### `\"" + std::string(row.name) + "\"`") != std::string::npos);
  }
}
