// `caustica plugins`: every plugin this build knows, family by family, from the registries; or,
// with --dict json|xml, the tokens for a libFuzzer dictionary of the scene readers.
#pragma once
#include <string>

namespace caustica {

struct PluginsArgs {
  std::string dict;  // empty: the listing; "json" or "xml": a fuzz dictionary's lines
};

int run_plugins(const PluginsArgs& args);

}  // namespace caustica
