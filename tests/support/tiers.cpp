#include "support/tiers.h"
#include <algorithm>
#define CATCH_CONFIG_EXTERNAL_INTERFACES  // the listener base
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

namespace caustica::test {

namespace {

bool in_figure_test = false;

bool has_tag(const Catch::TestCaseInfo& info, const std::string& tag) {
  return std::find(info.lcaseTags.begin(), info.lcaseTags.end(), tag) != info.lcaseTags.end();
}

// Notes whether the test case about to run is of the figure tier.
struct TierListener : Catch::TestEventListenerBase {
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseStarting(Catch::TestCaseInfo const& info) override { in_figure_test = has_tag(info, "figure"); }
  void testCaseEnded(Catch::TestCaseStats const& stats) override {
    in_figure_test = false;
    TestEventListenerBase::testCaseEnded(stats);
  }
};

}  // namespace

using Listener = TierListener;
CATCH_REGISTER_LISTENER(Listener)

bool figure_reduced() { return kFiguresReduced && in_figure_test; }

int figure_spp(int spp) { return figure_reduced() ? std::min(spp, 2) : spp; }

std::string figure_settings(const std::string& settings_json) {
  if (!figure_reduced()) return settings_json;
  nlohmann::json j = nlohmann::json::parse(settings_json);
  if (!j.is_object()) return settings_json;
  for (auto& [key, value] : j.items()) {
    const bool photons = key.size() >= 7 && key.compare(key.size() - 7, 7, "photons") == 0;
    if (photons && value.is_number() && value.get<double>() > 20000) value = 20000;
  }
  return j.dump();
}

TEST_CASE("tiers: every test case is in exactly one tier", TIER_UNIT) {
  int untiered = 0, several = 0;
  for (const Catch::TestCase& tc : Catch::getRegistryHub().getTestCaseRegistry().getAllTests()) {
    const int tiers = int(has_tag(tc, "unit")) + int(has_tag(tc, "figure")) + int(has_tag(tc, "process"));
    INFO(tc.name);
    CHECK(tiers == 1);
    untiered += tiers == 0;
    several += tiers > 1;
  }
  CHECK(untiered == 0);
  CHECK(several == 0);
}

}  // namespace caustica::test

