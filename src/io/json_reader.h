// Typed, validated reads from a JSON document that name the file and JSON pointer on error.
#pragma once
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>
#include "core/error.h"
#include "core/math.h"

namespace caustica {

// Parses JSON text; a syntax error becomes "file:line:column: message" with the line and a caret.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);

// For a document translated from another format (a Mitsuba XML scene): where each JSON pointer
// came from, e.g. "/materials/wood/alpha" -> "scene.xml:14:7: <float name=\"alpha\">".
using SourceMap = std::map<std::string, std::string>;

class JsonReader {
 public:
  explicit JsonReader(std::string file, std::shared_ptr<const SourceMap> sources = nullptr)
      : file_(std::move(file)), sources_(std::move(sources)) {}
  const std::string& file() const { return file_; }
  const std::shared_ptr<const SourceMap>& sources() const { return sources_; }

  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const;
  void warn(const std::string& pointer, const std::string& message, std::vector<std::string>& out) const;

  // Every key of `obj` must be in `known`; an object is required.
  void check_object(const nlohmann::json& obj, const std::string& pointer,
                    const std::vector<const char*>& known) const;
  const nlohmann::json& require(const nlohmann::json& obj, const std::string& pointer, const char* key) const;

  double number(const nlohmann::json& v, const std::string& pointer) const;  // finite, fits a float
  double number_in(const nlohmann::json& v, const std::string& pointer, double lo, double hi) const;
  int64_t integer(const nlohmann::json& v, const std::string& pointer, int64_t lo, int64_t hi) const;
  uint64_t unsigned_integer(const nlohmann::json& v, const std::string& pointer) const;  // 0 to 2^64 - 1
  bool boolean(const nlohmann::json& v, const std::string& pointer) const;
  std::string string(const nlohmann::json& v, const std::string& pointer) const;
  Vec3 vec3(const nlohmann::json& v, const std::string& pointer) const;
  // A position: three numbers within ±kMaxCoordinate (where single-precision rays are valid).
  Vec3 point(const nlohmann::json& v, const std::string& pointer) const;
  // Two numbers; `expected` names them in the message, e.g. "[u, v]".
  Vec2 vec2(const nlohmann::json& v, const std::string& pointer, const std::string& expected) const;
  Color color(const nlohmann::json& v, const std::string& pointer) const;  // non-negative
  // A file name, relative to `base_dir` unless absolute, that must name an existing regular
  // file; `what` names it in the message ("mesh file"). Returns the resolved path.
  std::string input_file(const nlohmann::json& v, const std::string& pointer, const std::string& base_dir,
                         const std::string& what) const;

 private:
  // "file: pointer" or, for a translated document, the place in the source it came from.
  std::string where(const std::string& pointer) const;
  std::string file_;
  std::shared_ptr<const SourceMap> sources_;
};

// Where a JSON block came from, so that later readers can name file and JSON pointer.
struct JsonSource {
  nlohmann::json value = nlohmann::json::object();
  std::string file;     // scene file name, for messages
  std::string pointer;  // JSON pointer of `value` inside the file
  std::shared_ptr<const SourceMap> sources;  // set when the scene was translated (Mitsuba XML)
};

// The message for a position or size past kMaxCoordinate: `what` names it ("coordinate 2e+18").
std::string out_of_scene_range(const std::string& what);

inline std::string child(const std::string& pointer, const std::string& key) { return pointer + "/" + key; }
inline std::string child(const std::string& pointer, size_t index) {
  return pointer + "/" + std::to_string(index);
}

}  // namespace caustica
