#pragma once
// Strict, path-aware reading of scene JSON. Every accessor records the key it was asked for, so
// finish() can reject any key nobody asked for (a typo is an error, not a silent default). Every
// error names the file, the JSON path (objects[2].material.poisson_ratio) and what is allowed.
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/scene/range.hpp"

namespace moreau {

class JsonObject {
 public:
  /// Throws an InputError if `value` is not a JSON object.
  JsonObject(const nlohmann::json& value, std::string path, std::string file);

  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  std::string path_of(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key) const;
  /// Records `key` as known without reading it.
  void allow(const std::string& key) const { known_.insert(key); }
  /// Declares every key this object may have (in the branch its reader took). A missing required
  /// key is then reported after any key outside this list, as that key with the closest allowed
  /// one suggested: a misspelt key is named as such, not as the key it was meant to be. The list
  /// only shapes messages; which keys are accepted is still decided by what is read.
  void expect_keys(std::vector<std::string> keys) const { expected_ = std::move(keys); }

  Real number(const std::string& key, Range range = Range::any()) const;
  Real number(const std::string& key, Real fallback, Range range = Range::any()) const;
  int integer(const std::string& key, int fallback, int min, int max = 1 << 30) const;
  int required_integer(const std::string& key, int min, int max = 1 << 30) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string choice(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed) const;
  Vec3 vec3(const std::string& key) const;
  Vec3 vec3(const std::string& key, const Vec3& fallback) const;
  Vec2 vec2(const std::string& key, Range range) const;
  std::vector<int> integers(const std::string& key, size_t count, int min) const;
  std::vector<int> integer_list(const std::string& key, int min) const;

  JsonObject object(const std::string& key) const;
  std::optional<JsonObject> optional_object(const std::string& key) const;
  std::vector<JsonObject> object_list(const std::string& key) const;
  const nlohmann::json& raw(const std::string& key) const;
  /// The object's keys (sorted), each recorded as known: for an object whose keys are names the
  /// scene chooses, read with number(key) and the like.
  std::vector<std::string> keys() const;

  /// Rejects keys that no accessor asked for.
  void finish() const;
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
  const nlohmann::json& require(const std::string& key) const;
  [[noreturn]] void fail_unknown(const std::string& key, const std::string& missing) const;
  const nlohmann::json* j_;
  std::string path_, file_;
  mutable std::set<std::string> known_;
  mutable std::vector<std::string> expected_;
};

/// The candidate nearest to `key` by edit distance (a swap of adjacent letters is one edit), or "" if none is within about a
/// third of the key's length (a typo, not a different word).
std::string closest_key(const std::string& key, const std::vector<std::string>& candidates);

/// Parses a scene file; syntax errors name line and column.
nlohmann::json parse_json_file(const std::string& path);
/// The same for JSON text; `source` names it in messages.
nlohmann::json parse_json_text(const std::string& text, const std::string& source);

/// Applies a command-line override `a.b.c=value`. Path segments index objects by key, arrays by
/// number or, for arrays of named objects, by "name". The value is parsed as JSON, or taken as a
/// string if it is not valid JSON.
void apply_override(nlohmann::json& scene, const std::string& assignment, const std::string& file);

}  // namespace moreau
