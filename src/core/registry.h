// What every family's registry table shares: rows with a `name`, looked up by it and listed
// for messages ("known: ...").
#pragma once
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace caustica {

class Params;

// The row of a family whose plugins are made from their block alone (textures, lights, media,
// phase functions, volumes): its name, whether Mitsuba 3 has a plugin of that name and
// parameters, its create function and every key its block may hold besides "type".
template <class Made>
struct FamilyRow {
  const char* name;
  bool mitsuba;
  std::unique_ptr<Made> (*create)(const Params&);
  std::vector<const char*> keys;
};
template <class Row>
struct is_family_row : std::false_type {};
template <class Made>
struct is_family_row<FamilyRow<Made>> : std::true_type {};

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
