#pragma once
// Where a spec of the scene builder came from (a file and a JSON path, or a scene built in code
// and its entry), and the checks the builder makes of each field. Every problem becomes an
// InputError "{source}: {path}.{field}: {problem}", so a value read from a file is reported at its
// JSON path (objects[2].material.poisson_ratio) and a value given in code at its entry.
#include <optional>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/scene/json_reader.hpp"
#include "moreau/scene/range.hpp"
#include "moreau/scene_builder.hpp"

namespace moreau {

class SpecPlace {
 public:
  SpecPlace(std::string source, std::string path) : source_(std::move(source)), path_(std::move(path)) {}
  /// The place of a JSON object: its file and path.
  explicit SpecPlace(const JsonObject& at) : SpecPlace(at.file(), at.path()) {}

  const std::string& path() const { return path_; }
  /// A nested place: path.field.
  SpecPlace at(const std::string& field) const { return {source_, path_of(field)}; }
  std::string path_of(const std::string& field) const { return path_.empty() ? field : path_ + "." + field; }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const;

  /// `value` if it is finite and inside `range`; fails "{value} is out of range; allowed: ..." else.
  Real number(const std::string& field, Real value, Range range = Range::any()) const;
  /// The same for a field that must be given.
  Real required(const std::string& field, const std::optional<double>& value, Range range = Range::any()) const;
  /// `value` inside [min, max].
  int integer(const std::string& field, int value, int min, int max = 1 << 30) const;
  /// A vector of finite numbers.
  Vec3 vector(const std::string& field, const Vector3& value) const;
  Vec3 required_vector(const std::string& field, const std::optional<Vector3>& value) const;
  /// Both entries inside `range`.
  Vec2 pair(const std::string& field, const Vector2& value, Range range = Range::any()) const;
  /// `value` if it is one of `allowed`.
  const std::string& choice(const std::string& field, const std::string& value, const std::vector<std::string>& allowed) const;

 private:
  std::string source_, path_;
};

inline Vec3 to_vec3(const Vector3& v) { return Vec3(v[0], v[1], v[2]); }
inline Vector3 to_vector3(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace moreau
