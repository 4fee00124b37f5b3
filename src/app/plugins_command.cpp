// `caustica plugins`.
#include "app/plugins_command.h"
#include <iostream>
#include <set>
#include "io/scene_loader.h"
#include "trace/integrator.h"

namespace caustica {
namespace {

std::vector<PluginListing> all_plugins() {
  std::vector<PluginListing> out = scene_plugins();
  for (const IntegratorPlugin& p : integrator_plugins()) {
    out.push_back({"integrator", p.name, false, std::vector<std::string>(p.keys.begin(), p.keys.end())});
  }
  return out;
}

// libFuzzer's dictionary syntax: one quoted token a line, quotes and backslashes escaped.
std::string dict_line(const std::string& token) {
  std::string out = "\"";
  for (char c : token) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

int run_plugins(const PluginsArgs& args) {
  const std::vector<PluginListing> plugins = all_plugins();
  if (args.dict.empty()) {
    for (const PluginListing& p : plugins) {
      std::cout << p.family << " " << p.name << (p.mitsuba ? " (Mitsuba)" : "") << ":";
      for (size_t i = 0; i < p.keys.size(); ++i) std::cout << (i ? ", " : " ") << p.keys[i];
      std::cout << "\n";
    }
    return 0;
  }
  // Tokens a mutation may need to reach each plugin's reader: its name and its keys, in the
  // form each format writes them.
  std::set<std::string> tokens;
  for (const PluginListing& p : plugins) {
    if (args.dict == "json") {
      tokens.insert("\"" + p.name + "\"");
      for (const std::string& k : p.keys) tokens.insert("\"" + k + "\":");
    } else if (p.mitsuba) {
      const std::string tag = p.family == "light" ? "emitter" : p.family;
      tokens.insert("<" + tag + " type=\"" + p.name + "\">");
      for (const std::string& k : p.keys) tokens.insert("name=\"" + k + "\"");
    }
  }
  for (const std::string& t : tokens) std::cout << dict_line(t) << "\n";
  return 0;
}

}  // namespace caustica
