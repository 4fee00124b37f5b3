// JSON parsing with file:line:column syntax errors and pointer-named semantic errors.
#include "io/json_reader.h"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

namespace caustica {

namespace {

// nlohmann::json parses iteratively, but copying, comparing and dumping a value recurse once per
// level: ~100k nested '[' overflow the stack (ASan: stack-overflow copying the integrator block).
// Scene files need a few levels, so a scan before parsing rejects anything deeper than kMaxDepth,
// skipping strings and comments the way the parser does.
constexpr int kMaxDepth = 512;

void check_nesting_depth(const std::string& text, const std::string& file) {
  int depth = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\') ++i;
      }
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      i = text.find('\n', i);
      if (i == std::string::npos) return;
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      i = text.find("*/", i + 2);
      if (i == std::string::npos) return;
      ++i;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth) {
        const size_t line = 1 + std::count(text.begin(), text.begin() + i, '\n');
        const size_t line_start = i == 0 ? std::string::npos : text.rfind('\n', i - 1);
        const size_t column = line_start == std::string::npos ? i + 1 : i - line_start;
        throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": nesting deeper than " +
                         std::to_string(kMaxDepth) + " levels");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

}  // namespace

namespace {
// Refuses a key given twice in one object (JSON allows it, the last one would silently win),
// naming the object by its JSON pointer: the parser's callback sees every object, key and value.
class DuplicateKeys {
 public:
  explicit DuplicateKeys(std::string file) : file_(std::move(file)) {}
  bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start: frames_.push_back({true, {}, {}, 0}); break;
      case E::array_start: frames_.push_back({false, {}, {}, 0}); break;
      case E::key: {
        Frame& f = frames_.back();
        const std::string key = parsed.get<std::string>();
        if (!f.keys.insert(key).second) {
          throw InputError(file_ + ": " + pointer() + ": key \"" + key + "\" is given twice (give each key once)");
        }
        f.last_key = key;
        break;
      }
      case E::object_end:
      case E::array_end:
        frames_.pop_back();
        element_done();
        break;
      case E::value: element_done(); break;
    }
    return true;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string last_key;
    size_t index;
  };
  void element_done() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  // The pointer of the innermost open object: each enclosing frame's current key or index.
  std::string pointer() const {
    std::string p;
    for (size_t i = 0; i + 1 < frames_.size(); ++i) {
      p += "/" + (frames_[i].object ? frames_[i].last_key : std::to_string(frames_[i].index));
    }
    return p.empty() ? "the top level" : p;
  }
  std::string file_;
  std::vector<Frame> frames_;
};
}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
  check_nesting_depth(text, file);
  try {
    return nlohmann::json::parse(text, DuplicateKeys(file), true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset of the character where parsing stopped.
    // e.byte is just past the token that failed; step back to the token's first character.
    size_t stop = std::min<size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    if (stop < text.size() && stop > 0) {
      if (text[stop] == '"') {
        const size_t open = text.rfind('"', stop - 1);
        if (open != std::string::npos && text.find('\n', open) >= stop) stop = open;
      } else {
        auto token_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+'; };
        if (token_char(text[stop])) {
          while (stop > 0 && token_char(text[stop - 1])) --stop;
        }
      }
    }
    size_t line = 1, line_start = 0;
    for (size_t i = 0; i < stop; ++i) {
      if (text[i] == '\n') {
        ++line;
        line_start = i + 1;
      }
    }
    const size_t column = stop - line_start + 1;
    std::string what = e.what();
    const size_t s = what.find("syntax error");
    if (s != std::string::npos) what = what.substr(s);
    size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    std::string source_line = text.substr(line_start, std::min<size_t>(line_end - line_start, 200));
    for (char& c : source_line) {
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    }
    std::ostringstream msg;
    msg << file << ":" << line << ":" << column << ": " << what;
    if (!source_line.empty()) {
      msg << "\n  " << source_line << "\n  " << std::string(std::min<size_t>(column - 1, 200), ' ') << "^";
    }
    throw InputError(msg.str());
  } catch (const nlohmann::json::exception& e) {
    // Number overflow ("1e999") carries no position: find the quoted token in the text.
    std::string what = e.what();
    const size_t q1 = what.find('\''), q2 = what.rfind('\'');
    std::string where = file;
    if (q1 != std::string::npos && q2 > q1) {
      const std::string token = what.substr(q1 + 1, q2 - q1 - 1);
      // The first occurrence outside a string literal.
      bool in_string = false;
      size_t at = std::string::npos;
      for (size_t i = 0; i < text.size(); ++i) {
        if (in_string) {
          if (text[i] == '\\') ++i;
          else if (text[i] == '"') in_string = false;
        } else if (text[i] == '"') {
          in_string = true;
        } else if (text.compare(i, token.size(), token) == 0) {
          at = i;
          break;
        }
      }
      if (at != std::string::npos) {
        const size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
        const size_t line_start = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
        const size_t column = line_start == std::string::npos ? at + 1 : at - line_start;
        where += ":" + std::to_string(line) + ":" + std::to_string(column);
      }
    }
    const size_t bracket = what.find("] ");
    throw InputError(where + ": " + (bracket != std::string::npos ? what.substr(bracket + 2) : what));
  }
}

std::string JsonReader::where(const std::string& pointer) const {
  if (sources_) {
    // The longest recorded prefix of the pointer, and the keys below it.
    for (std::string p = pointer;; p = p.substr(0, p.rfind('/'))) {
      const auto it = sources_->find(p);
      if (it != sources_->end()) {
        std::string rest = pointer.substr(p.size());
        if (!rest.empty() && rest[0] == '/') rest = rest.substr(1);
        return it->second + (rest.empty() ? "" : ": " + rest);
      }
      if (p.empty()) break;
    }
  }
  return file_ + ": " + (pointer.empty() ? "/" : pointer);
}

void JsonReader::fail(const std::string& pointer, const std::string& message) const {
  throw InputError(where(pointer) + ": " + message);
}

void JsonReader::warn(const std::string& pointer, const std::string& message, std::vector<std::string>& out) const {
  out.push_back(where(pointer) + ": " + message);
}

static std::string type_name(const nlohmann::json& v) { return v.type_name(); }

void JsonReader::check_object(const nlohmann::json& obj, const std::string& pointer,
                              const std::vector<const char*>& known) const {
  if (!obj.is_object()) fail(pointer, "expected an object, found " + type_name(obj));
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (!ok) {
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      fail(child(pointer, it.key()), "unknown key \"" + it.key() + "\" (known: " + list + ")");
    }
  }
}

const nlohmann::json& JsonReader::require(const nlohmann::json& obj, const std::string& pointer, const char* key) const {
  auto it = obj.find(key);
  if (it == obj.end()) fail(pointer, std::string("missing required key \"") + key + "\"");
  return *it;
}

double JsonReader::number(const nlohmann::json& v, const std::string& pointer) const {
  if (!v.is_number()) fail(pointer, "expected a number, found " + type_name(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(pointer, "number is not finite");
  // Every number is stored as a float: 1e308 would become inf (and converting a double outside
  // the float range is undefined behaviour), turning the camera or bounds into NaN.
  if (std::abs(d) > std::numeric_limits<float>::max()) fail(pointer, "number is too large (beyond the float range, about 3.4e38)");
  return d;
}

double JsonReader::number_in(const nlohmann::json& v, const std::string& pointer, double lo, double hi) const {
  const double d = number(v, pointer);
  if (d < lo || d > hi) {
    std::ostringstream m;
    m << "value " << d << " is out of range [" << lo << ", " << hi << "]";
    fail(pointer, m.str());
  }
  return d;
}

int64_t JsonReader::integer(const nlohmann::json& v, const std::string& pointer, int64_t lo, int64_t hi) const {
  if (!v.is_number_integer()) fail(pointer, "expected an integer, found " + type_name(v));
  // An unsigned value past INT64_MAX is past every range here (it was clamped silently before).
  const bool too_big = v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX);
  const int64_t i = too_big ? INT64_MAX : v.get<int64_t>();
  if (too_big || i < lo || i > hi) {
    // v.dump() prints the number as written.
    fail(pointer, "value " + v.dump() + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return i;
}

uint64_t JsonReader::unsigned_integer(const nlohmann::json& v, const std::string& pointer) const {
  if (!v.is_number_integer() || (!v.is_number_unsigned() && v.get<int64_t>() < 0)) {
    fail(pointer, "expected a whole number from 0 to 2^64 - 1, found " + (v.is_number() ? v.dump() : type_name(v)));
  }
  return v.get<uint64_t>();
}

bool JsonReader::boolean(const nlohmann::json& v, const std::string& pointer) const {
  if (!v.is_boolean()) fail(pointer, "expected true or false, found " + type_name(v));
  return v.get<bool>();
}

std::string JsonReader::string(const nlohmann::json& v, const std::string& pointer) const {
  if (!v.is_string()) fail(pointer, "expected a string, found " + type_name(v));
  return v.get<std::string>();
}

std::string JsonReader::input_file(const nlohmann::json& v, const std::string& pointer, const std::string& base_dir,
                                   const std::string& what) const {
  namespace fs = std::filesystem;
  const std::string name = string(v, pointer);
  const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : fs::path(base_dir) / name;
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(pointer, what + " not found: tried " + path.string());
  if (!fs::is_regular_file(path, ec)) fail(pointer, what + " is not a regular file: " + path.string());
  return path.string();
}

Vec3 JsonReader::vec3(const nlohmann::json& v, const std::string& pointer) const {
  if (!v.is_array() || v.size() != 3) fail(pointer, "expected an array of 3 numbers");
  return Vec3(static_cast<float>(number(v[0], child(pointer, 0))),
              static_cast<float>(number(v[1], child(pointer, 1))),
              static_cast<float>(number(v[2], child(pointer, 2))));
}

std::string out_of_scene_range(const std::string& what) {
  return what + " is out of range: positions and sizes must lie within " + format_number(kMaxCoordinate) +
         " of the origin (the renderer computes in single precision)";
}

Vec3 JsonReader::point(const nlohmann::json& v, const std::string& pointer) const {
  const Vec3 x = vec3(v, pointer);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(x[i]) > kMaxCoordinate) fail(child(pointer, i), out_of_scene_range("coordinate " + format_number(x[i])));
  }
  return x;
}

Vec2 JsonReader::vec2(const nlohmann::json& v, const std::string& pointer, const std::string& expected) const {
  if (!v.is_array() || v.size() != 2) fail(pointer, "expected " + expected);
  return Vec2(static_cast<float>(number(v[0], child(pointer, 0))), static_cast<float>(number(v[1], child(pointer, 1))));
}

Color JsonReader::color(const nlohmann::json& v, const std::string& pointer) const {
  if (v.is_number()) {
    const float c = static_cast<float>(number_in(v, pointer, 0.0, kMaxColor));
    return Color(c);
  }
  const Vec3 c = vec3(v, pointer);
  for (int i = 0; i < 3; ++i) {
    if (c[i] < 0.0f) fail(child(pointer, size_t(i)), "colour components must not be negative");
    if (c[i] > kMaxColor) fail(child(pointer, size_t(i)), "value " + format_number(c[i]) + " is out of range [0, " + format_number(kMaxColor) + "]");
  }
  return c;
}

}  // namespace caustica
