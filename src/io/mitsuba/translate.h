// A Mitsuba scene (xml_tree.h) turned into the JSON document of our own format, so that the one
// scene loader builds both; every JSON pointer made is mapped back to its file:line:column.
// What maps to what is in docs/mitsuba.md.
#pragma once
#include <memory>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>
#include "io/json_reader.h"
#include "io/mitsuba/xml_tree.h"

namespace caustica {

struct MitsubaOptions {
  XmlOptions xml;
  // Unsupported plugins become warnings: the object is skipped or replaced (the warning says which).
  bool ignore_unsupported = false;
  // Set when the command line chooses the integrator ("--integrator photon"): a scene's
  // <integrator> of a type we do not have is then not interpreted (only its max_depth is kept),
  // and a warning says it was replaced.
  std::string integrator_replaced_by;
};

struct TranslatedScene {
  nlohmann::json doc;
  std::shared_ptr<SourceMap> sources;
  std::vector<std::string> warnings;
};

TranslatedScene translate_mitsuba(const XmlScene& scene, const MitsubaOptions& options);

// Reads and translates a Mitsuba XML text (`file` names it; relative paths resolve against `dir`).
TranslatedScene read_mitsuba(const std::string& text, const std::string& file, const std::string& dir,
                             const MitsubaOptions& options);

}  // namespace caustica
