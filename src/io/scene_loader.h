// Reads JSON scene files (format: docs/scene-format.md).
#pragma once
#include <string>
#include <vector>
#include "io/mitsuba/translate.h"
#include "core/scene.h"

namespace caustica {

struct LoadedScene {
  std::unique_ptr<Scene> scene;
  std::vector<std::string> warnings;
  std::string integrator_type = "path";
  JsonSource integrator_settings;  // the integrator block without "type" (the integrator reads it)
  size_t triangle_count = 0, sphere_count = 0;
};

// Throws InputError naming the file and the place in it. A file whose text starts with '<' is a
// Mitsuba XML scene (read by its root element, not its extension); anything else is our JSON.
LoadedScene load_scene(const std::string& path, const MitsubaOptions& mitsuba = {});
// Parses scene text; `file` names it in messages, `base_dir` resolves mesh paths.
LoadedScene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir,
                        const MitsubaOptions& mitsuba = {});

}  // namespace caustica
