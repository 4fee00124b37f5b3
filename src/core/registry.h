// What every family's registry table shares: rows with a `name`, looked up by it and listed
// for messages ("known: ...").
#pragma once
#include <string>
#include <vector>

namespace caustica {

// The row named `name`, or nullptr.
template <class Plugin>
const Plugin* find_plugin(const std::vector<Plugin>& table, const std::string& name) {
  for (const Plugin& p : table) {
    if (name == p.name) return &p;
  }
  return nullptr;
}

// "a, b, c": the table's names in order.
template <class Plugin>
std::string plugin_names(const std::vector<Plugin>& table) {
  std::string out;
  for (const Plugin& p : table) out += (out.empty() ? "" : ", ") + std::string(p.name);
  return out;
}

}  // namespace caustica
