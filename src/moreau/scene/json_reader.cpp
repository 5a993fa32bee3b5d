#include "moreau/scene/json_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "moreau/errors.hpp"

namespace moreau {

using nlohmann::json;

namespace {
std::string type_name(const json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return "null";
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out;
}
}  // namespace

JsonObject::JsonObject(const json& value, std::string path, std::string file)
    : j_(&value), path_(std::move(path)), file_(std::move(file)) {
  if (!value.is_object())
    throw InputError(fmt::format("{}: {}: expected an object, found {}", file_, path_.empty() ? "(top level)" : path_,
                                 type_name(value)));
}

bool JsonObject::has(const std::string& key) const {
  known_.insert(key);
  return j_->contains(key);
}

void JsonObject::fail(const std::string& key, const std::string& problem) const {
  throw InputError(fmt::format("{}: {}: {}", file_, path_of(key), problem));
}

namespace {
// Edit distance counting a changed, added or dropped letter, or two adjacent letters swapped, as
// one edit (optimal string alignment, a full matrix: keys are short).
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}
}  // namespace

std::string closest_key(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(2, key.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const size_t distance = edit_distance(key, c);
    if (distance < best_distance) best_distance = distance, best = c;
  }
  return best;
}

void JsonObject::fail_unknown(const std::string& key, const std::string& missing) const {
  std::vector<std::string> allowed = expected_;
  for (const std::string& k : known_)
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) allowed.push_back(k);
  std::string suggestion = closest_key(key, allowed);
  if (suggestion.empty() && !missing.empty()) suggestion = missing;
  const std::string hint = suggestion.empty() ? ""
                           : suggestion == missing
                               ? fmt::format(" (did you mean '{}', which is required here?)", suggestion)
                               : fmt::format(" (did you mean '{}'?)", suggestion);
  fail(key, fmt::format("unknown key{}; allowed here: {}", hint, join(allowed)));
}

const json& JsonObject::require(const std::string& key) const {
  known_.insert(key);
  auto it = j_->find(key);
  if (it == j_->end()) {
    // A key outside the declared list (or, with none declared, a near-spelling of this key that
    // nothing has read) is the user's real mistake: name it first.
    for (auto other = j_->begin(); other != j_->end(); ++other) {
      if (known_.count(other.key())) continue;
      if (expected_.empty()) {
        // Without a declared list the other key may be one still to be read: only a near-miss
        // spelling of this one (a letter changed, added, dropped or two swapped) is named.
        if (key.size() >= 4 && edit_distance(other.key(), key) == 1)
          fail(other.key(), fmt::format("unknown key (did you mean '{}', which is required here?)", key));
      } else if (std::find(expected_.begin(), expected_.end(), other.key()) == expected_.end()) {
        fail_unknown(other.key(), key);
      }
    }
    fail(key, "missing required key");
  }
  return *it;
}

const json& JsonObject::raw(const std::string& key) const { return require(key); }

Real JsonObject::number(const std::string& key, Range range) const {
  const json& v = require(key);
  if (!v.is_number()) fail(key, fmt::format("expected a number, found {}", type_name(v)));
  const Real x = v.get<Real>();
  if (!std::isfinite(x) || !range.contains(x))
    fail(key, fmt::format("{} is out of range; allowed: {}", x, range.describe()));
  return x;
}

Real JsonObject::number(const std::string& key, Real fallback, Range range) const {
  return has(key) ? number(key, range) : fallback;
}

int JsonObject::required_integer(const std::string& key, int min, int max) const {
  const json& v = require(key);
  if (!v.is_number_integer()) fail(key, fmt::format("expected an integer, found {}", v.dump()));
  const long long x = v.get<long long>();
  if (x < min || x > max) fail(key, fmt::format("{} is out of range; allowed: [{}, {}]", x, min, max));
  return static_cast<int>(x);
}

int JsonObject::integer(const std::string& key, int fallback, int min, int max) const {
  return has(key) ? required_integer(key, min, max) : fallback;
}

bool JsonObject::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const json& v = require(key);
  if (!v.is_boolean()) fail(key, fmt::format("expected true or false, found {}", type_name(v)));
  return v.get<bool>();
}

std::string JsonObject::string(const std::string& key) const {
  const json& v = require(key);
  if (!v.is_string()) fail(key, fmt::format("expected a string, found {}", type_name(v)));
  return v.get<std::string>();
}

std::string JsonObject::choice(const std::string& key, const std::vector<std::string>& allowed) const {
  const std::string s = string(key);
  for (const auto& a : allowed)
    if (s == a) return s;
  fail(key, fmt::format("'{}' is not valid; allowed: {}", s, join(allowed)));
}

std::string JsonObject::choice(const std::string& key, const std::string& fallback,
                               const std::vector<std::string>& allowed) const {
  return has(key) ? choice(key, allowed) : fallback;
}

Vec3 JsonObject::vec3(const std::string& key) const {
  const json& v = require(key);
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    fail(key, fmt::format("expected an array of 3 numbers, found {}", v.dump()));
  return Vec3(v[0].get<Real>(), v[1].get<Real>(), v[2].get<Real>());
}

Vec3 JsonObject::vec3(const std::string& key, const Vec3& fallback) const { return has(key) ? vec3(key) : fallback; }

Vec2 JsonObject::vec2(const std::string& key, Range range) const {
  const json& v = require(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    fail(key, fmt::format("expected an array of 2 numbers, found {}", v.dump()));
  const Vec2 out(v[0].get<Real>(), v[1].get<Real>());
  if (!range.contains(out.x()) || !range.contains(out.y()))
    fail(key, fmt::format("{} is out of range; each entry allowed: {}", v.dump(), range.describe()));
  return out;
}

std::vector<int> JsonObject::integers(const std::string& key, size_t count, int min) const {
  const json& v = require(key);
  bool ok = v.is_array() && v.size() == count;
  for (size_t i = 0; ok && i < v.size(); ++i) ok = v[i].is_number_integer() && v[i].get<long long>() >= min;
  if (!ok) fail(key, fmt::format("expected an array of {} integers >= {}, found {}", count, min, v.dump()));
  return v.get<std::vector<int>>();
}

std::vector<int> JsonObject::integer_list(const std::string& key, int min) const {
  const json& v = require(key);
  bool ok = v.is_array();
  for (size_t i = 0; ok && i < v.size(); ++i) ok = v[i].is_number_integer() && v[i].get<long long>() >= min;
  if (!ok) fail(key, fmt::format("expected an array of integers >= {}, found {}", min, v.dump()));
  return v.get<std::vector<int>>();
}

JsonObject JsonObject::object(const std::string& key) const { return JsonObject(require(key), path_of(key), file_); }

std::optional<JsonObject> JsonObject::optional_object(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return object(key);
}

std::vector<JsonObject> JsonObject::object_list(const std::string& key) const {
  std::vector<JsonObject> out;
  if (!has(key)) return out;
  const json& v = require(key);
  if (!v.is_array()) fail(key, fmt::format("expected an array, found {}", type_name(v)));
  for (size_t i = 0; i < v.size(); ++i) out.emplace_back(v[i], fmt::format("{}[{}]", path_of(key), i), file_);
  return out;
}

std::vector<std::string> JsonObject::keys() const {
  std::vector<std::string> out;
  for (auto it = j_->begin(); it != j_->end(); ++it) out.push_back(it.key());
  known_.insert(out.begin(), out.end());
  return out;
}

void JsonObject::finish() const {
  for (auto it = j_->begin(); it != j_->end(); ++it)
    if (!known_.count(it.key())) fail_unknown(it.key(), "");
}

namespace {

// Line and column of a byte offset.
std::pair<size_t, size_t> line_and_column(const std::string& text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < std::min(offset, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Rejects an object that repeats a key (JSON leaves it undefined; nlohmann keeps the last value
// silently): tracks the keys seen in each open object, and the JSON path for the message.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: open_.push_back({true, {}, {}, 0}); break;
      case json::parse_event_t::array_start: open_.push_back({false, {}, {}, 0}); break;
      case json::parse_event_t::key: {
        Level& top = open_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second)
          throw InputError(fmt::format("{}: {}: the key appears twice in this object; give it once", file_, path()));
        break;
      }
      case json::parse_event_t::value: element_done(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        open_.pop_back();
        element_done();
        break;
    }
    return true;
  }

  /// The JSON path of the value being parsed (e.g. "settings.dt").
  std::string path() const {
    std::string p;
    for (const Level& l : open_) p += l.is_object ? (p.empty() ? "" : ".") + l.key : fmt::format("[{}]", l.index);
    return p;
  }

 private:
  struct Level {
    bool is_object;
    std::set<std::string> keys;
    std::string key;
    size_t index;
  };
  void element_done() {
    if (!open_.empty() && !open_.back().is_object) ++open_.back().index;
  }
  std::string file_;
  std::vector<Level> open_;
};

}  // namespace

json parse_json_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a directory; give the path of a scene file (.json)", path));
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open scene file (does it exist and is it readable?)", path));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_json_text(buffer.str(), path);
}

json parse_json_text(const std::string& text, const std::string& path) {
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    const auto [line, column] = line_and_column(text, nul);
    throw InputError(fmt::format("{}:{}:{}: the file contains a NUL byte; a scene file is UTF-8 JSON text", path, line, column));
  }
  DuplicateKeyCheck check(path);  // shared with the parser, so that an overflow can name its path
  try {
    return json::parse(text, [&check](int depth, json::parse_event_t event, json& parsed) { return check(depth, event, parsed); });
  } catch (const json::parse_error& e) {
    const auto [line, column] = line_and_column(text, e.byte == 0 ? 0 : e.byte - 1);
    std::string what = e.what();
    const auto colon = what.find("syntax error");
    throw InputError(fmt::format("{}:{}:{}: malformed JSON: {}", path, line, column,
                                 colon == std::string::npos ? what : what.substr(colon)));
  } catch (const json::out_of_range& e) {
    // A number too large for a double (1e999): nlohmann says "number overflow parsing '1e999'".
    const std::string what = e.what();
    const auto quote = what.find('\'');
    throw InputError(fmt::format("{}: {}: the number {} does not fit a double (|x| < 1.8e308)", path, check.path(),
                                 quote == std::string::npos ? std::string("given") : what.substr(quote)));
  }
}

void apply_override(json& scene, const std::string& assignment, const std::string& file) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(fmt::format("--set '{}': expected path=value, e.g. settings.substeps=40", assignment));
  const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  json value;
  try {
    value = json::parse(text);
  } catch (const json::parse_error&) {
    value = text;  // a bare word is a string
  } catch (const json::out_of_range&) {
    throw InputError(fmt::format("--set {}: '{}' does not fit a double (|x| < 1.8e308)", assignment, text));
  }
  json* node = &scene;
  std::string walked;
  std::stringstream segments(path);
  std::string segment;
  std::vector<std::string> parts;
  while (std::getline(segments, segment, '.')) parts.push_back(segment);
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& s = parts[i];
    const bool last = i + 1 == parts.size();
    walked += (walked.empty() ? "" : ".") + s;
    if (node->is_array()) {
      json* next = nullptr;
      if (!s.empty() && s.find_first_not_of("0123456789") == std::string::npos) {
        // An index of more digits than any array's size has is past the end (stoul would throw).
        const size_t k = s.size() <= 9 ? std::stoul(s) : node->size();
        if (k < node->size()) next = &(*node)[k];
      } else {
        for (auto& item : *node)
          if (item.is_object() && item.value("name", "") == s) next = &item;
      }
      if (!next)
        throw InputError(fmt::format("{}: --set {}: no element '{}' in this array (use an index or an object name)", file,
                                     path, walked));
      node = next;
    } else if (node->is_object()) {
      if (!last && !node->contains(s)) (*node)[s] = json::object();
      node = &(*node)[s];
    } else {
      throw InputError(fmt::format("{}: --set {}: '{}' is not an object or array", file, path, walked));
    }
    if (last) {
      // An object value replaces the whole object (settings.linear_solver={"type": "direct"});
      // an empty one would silently reset every key in it (--set settings={}).
      if (node->is_object() && !node->empty() && value.is_object() && value.empty())
        throw InputError(fmt::format("{}: --set {}: '{}' is an object; set its keys one at a time (e.g. --set {}.{}=...)",
                                     file, path, walked, walked, node->begin().key()));
      *node = value;
    }
  }
}

}  // namespace moreau
