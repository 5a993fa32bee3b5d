#include "moreau/scene/spec_place.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "moreau/errors.hpp"

namespace moreau {

std::string Range::describe() const {
  const bool has_lo = lo > -1e299, has_hi = hi < 1e299;
  if (has_lo && has_hi) return fmt::format("{}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
  if (has_lo) return fmt::format("{} {}", lo_open ? ">" : ">=", lo);
  if (has_hi) return fmt::format("{} {}", hi_open ? "<" : "<=", hi);
  return "any number";
}

void SpecPlace::fail(const std::string& field, const std::string& problem) const {
  throw InputError(fmt::format("{}: {}: {}", source_, path_of(field), problem));
}

Real SpecPlace::number(const std::string& field, Real value, Range range) const {
  if (!std::isfinite(value) || !range.contains(value))
    fail(field, fmt::format("{} is out of range; allowed: {}", value, range.describe()));
  return value;
}

Real SpecPlace::required(const std::string& field, const std::optional<double>& value, Range range) const {
  if (!value) fail(field, "missing required key");
  return number(field, *value, range);
}

int SpecPlace::integer(const std::string& field, int value, int min, int max) const {
  if (value < min || value > max) fail(field, fmt::format("{} is out of range; allowed: [{}, {}]", value, min, max));
  return value;
}

Vec3 SpecPlace::vector(const std::string& field, const Vector3& value) const {
  for (double v : value)
    if (!std::isfinite(v)) fail(field, fmt::format("[{}] is not a vector of finite numbers", fmt::join(value, ", ")));
  return to_vec3(value);
}

Vec3 SpecPlace::required_vector(const std::string& field, const std::optional<Vector3>& value) const {
  if (!value) fail(field, "missing required key");
  return vector(field, *value);
}

Vec2 SpecPlace::pair(const std::string& field, const Vector2& value, Range range) const {
  for (double v : value)
    if (!std::isfinite(v) || !range.contains(v))
      fail(field, fmt::format("[{}] is out of range; each entry allowed: {}", fmt::join(value, ", "), range.describe()));
  return Vec2(value[0], value[1]);
}

const std::string& SpecPlace::choice(const std::string& field, const std::string& value,
                                     const std::vector<std::string>& allowed) const {
  for (const auto& a : allowed)
    if (value == a) return value;
  fail(field, fmt::format("'{}' is not valid; allowed: {}", value, fmt::join(allowed, ", ")));
}

}  // namespace moreau
