// Reads JSON scene files (format: docs/scene-format.md).
#pragma once
#include <string>
#include <vector>
#include "core/scene.h"

namespace caustica {

struct LoadedScene {
  std::unique_ptr<Scene> scene;
  std::vector<std::string> warnings;
  size_t triangle_count = 0, sphere_count = 0;
};

// Throws InputError naming the file and the place in it.
LoadedScene load_scene(const std::string& path);
// Parses scene text; `file` names it in messages, `base_dir` resolves mesh paths.
LoadedScene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir);

}  // namespace caustica
