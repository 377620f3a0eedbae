#pragma once
// One reader for every JSON input (scene files, --set values, lenses, materials, minerals,
// thin sections, 3-D scenes, vignetting tables): the same mistake gets the same message in every
// file type. Errors are InputError with the file, the full dot path of the key ("front.radius_mm",
// "grains[3].x_axis"), the value as written and the reason.
#include <array>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/base/input_error.h"

namespace pmsim {

// Thrown by a value conversion with the reason only; the reader (or a caller that knows the key
// path) turns it into an InputError.
struct BadValue {
  std::string why;
};

// A value's text as the user wrote it: strings unquoted, anything else as compact JSON.
std::string shown(const nlohmann::json& v);
// Numbers in messages: integers exactly, others in their shortest round-trip form (0.3).
std::string number_text(double v);

// An interval a number must lie in; its message reads "must be in (0, 1000]" or "must be > 0".
struct Range {
  double lo = -1e308, hi = 1e308;
  bool lo_open = false, hi_open = false;
  bool contains(double v) const;
  std::string message() const;
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  static Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }
  static Range above(double lo) { return {lo, 1e308, true, false}; }
  static Range at_least(double lo) { return {lo, 1e308, false, false}; }
};

// The names of an enum's values as spelled in files (matched case-insensitively).
template <class E>
struct NameTable {
  std::vector<std::pair<std::string, E>> entries;
  NameTable(std::initializer_list<std::pair<const char*, E>> l) {
    for (const auto& [n, e] : l) entries.emplace_back(n, e);
  }
  std::string list() const {  // "a|b|c"
    std::string all;
    for (const auto& [n, e] : entries) all += (all.empty() ? "" : "|") + n;
    return all;
  }
  const std::string& name(E e) const {
    for (const auto& [n, x] : entries)
      if (x == e) return n;
    return entries.front().first;
  }
  std::optional<E> find(std::string_view lower_name) const {
    for (const auto& [n, e] : entries)
      if (lower_name == n) return e;
    return std::nullopt;
  }
};

// Conversions of one value; throw BadValue. "expected a number", "expected an integer",
// "expected true or false", "expected a string", "expected a vector [x, y, z]".
double number_value(const nlohmann::json& v);
int integer_value(const nlohmann::json& v);
bool bool_value(const nlohmann::json& v);
std::string string_value(const nlohmann::json& v);  // well-formed UTF-8 only
std::array<double, 3> vector3_value(const nlohmann::json& v);
// Normalised; the zero vector is refused. A vector already unit to rounding is kept as written,
// so that save → load does not change its last bit.
std::array<double, 3> unit_vector_value(const nlohmann::json& v);
std::string lower_string_value(const nlohmann::json& v);
template <class E>
E enum_value(const nlohmann::json& v, const NameTable<E>& names) {
  if (auto e = names.find(lower_string_value(v))) return *e;
  throw BadValue{"expected one of " + names.list()};
}

template <class T>
T json_value(const nlohmann::json& v);
template <>
inline double json_value<double>(const nlohmann::json& v) {
  return number_value(v);
}
template <>
inline int json_value<int>(const nlohmann::json& v) {
  return integer_value(v);
}
template <>
inline bool json_value<bool>(const nlohmann::json& v) {
  return bool_value(v);
}
template <>
inline std::string json_value<std::string>(const nlohmann::json& v) {
  return string_value(v);
}
template <>
inline std::array<double, 3> json_value<std::array<double, 3>>(const nlohmann::json& v) {
  return vector3_value(v);
}

// The bytes of a file; InputError naming the file when it is missing, a folder or unreadable.
std::string read_text_file(const std::string& path, const std::string& what);
// Parses a JSON file; InputError naming the file when it is missing, a folder, unreadable or not
// JSON (numbers beyond double included). `what` names the file type in messages ("lens file").
nlohmann::json read_json_file(const std::string& path, const std::string& what);

// A JSON object being read, with its file and the dot path that leads to it.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& j, std::string file, std::string prefix = "",
             std::vector<std::string>* warnings = nullptr);

  const nlohmann::json& node() const { return *j_; }
  const std::string& file() const { return file_; }
  const std::string& prefix() const { return prefix_; }
  // The full key path of `key` (a dot path relative to this object).
  std::string path(std::string_view key) const;
  // The value at dot path `key`; nullptr when absent. A value of JSON null counts as absent
  // only in optional reads that say so (null_is_absent).
  const nlohmann::json* find(std::string_view key) const;
  bool has(std::string_view key) const { return find(key) != nullptr; }

  template <class T>
  T require(std::string_view key) const {
    return convert<T>(key, required(key));
  }
  template <class T>
  T require(std::string_view key, const Range& r) const {
    return in_range(key, required(key), convert<T>(key, required(key)), r);
  }
  template <class T>
  std::optional<T> optional(std::string_view key) const {
    const nlohmann::json* v = find(key);
    if (!v) return std::nullopt;
    return convert<T>(key, *v);
  }
  template <class T>
  std::optional<T> optional(std::string_view key, const Range& r) const {
    const nlohmann::json* v = find(key);
    if (!v) return std::nullopt;
    return in_range(key, *v, convert<T>(key, *v), r);
  }
  template <class T>
  T get_or(std::string_view key, T fallback) const {
    return optional<T>(key).value_or(std::move(fallback));
  }
  template <class T>
  T get_or(std::string_view key, T fallback, const Range& r) const {
    return optional<T>(key, r).value_or(std::move(fallback));
  }
  std::array<double, 3> require_unit_vector(std::string_view key) const;
  std::optional<std::array<double, 3>> optional_unit_vector(std::string_view key) const;
  template <class E>
  E require_enum(std::string_view key, const NameTable<E>& names) const {
    return checked(key, required(key), [&](const nlohmann::json& v) { return enum_value(v, names); });
  }
  template <class E>
  std::optional<E> optional_enum(std::string_view key, const NameTable<E>& names) const {
    const nlohmann::json* v = find(key);
    if (!v) return std::nullopt;
    return checked(key, *v, [&](const nlohmann::json& x) { return enum_value(x, names); });
  }

  // A nested object: "expected an object" when `key` holds anything else.
  JsonReader object(std::string_view key) const;
  std::optional<JsonReader> optional_object(std::string_view key) const;
  // The objects of an array at `key` (paths "key[i]"); "expected an array of at least n objects".
  std::vector<JsonReader> objects(std::string_view key, std::size_t min_size = 0) const;

  // Keys of this object not in `known`: each is a warning "unknown key 'path' ignored" (files
  // whose readers accept annotations of any name) or, with refuse, the error "unknown key".
  void warn_unknown_keys(std::initializer_list<std::string_view> known) const;
  void refuse_unknown_keys(std::initializer_list<std::string_view> known) const;
  void warn(const std::string& message) const;

  // Runs f(value) and reports a BadValue or a json exception it throws on `key`.
  template <class F>
  auto checked(std::string_view key, const nlohmann::json& v, F&& f) const -> decltype(f(v)) {
    try {
      return f(v);
    } catch (const BadValue& b) {
      fail(key, v, b.why);
    } catch (const nlohmann::json::exception& e) {
      fail(key, v, e.what());
    }
  }
  [[noreturn]] void fail(std::string_view key, const nlohmann::json& value, const std::string& why) const;
  [[noreturn]] void fail(std::string_view key, const std::string& why) const;  // value as found

 private:
  const nlohmann::json& required(std::string_view key) const;
  template <class T>
  T convert(std::string_view key, const nlohmann::json& v) const {
    return checked(key, v, [](const nlohmann::json& x) { return json_value<T>(x); });
  }
  template <class T>
  T in_range(std::string_view key, const nlohmann::json& v, T x, const Range& r) const {
    if (!r.contains(static_cast<double>(x))) fail(key, v, r.message());
    return x;
  }
  std::vector<std::string> unknown_keys(std::initializer_list<std::string_view> known) const;

  const nlohmann::json* j_;
  std::string file_;
  std::string prefix_;
  std::vector<std::string>* warnings_;
};

}  // namespace pmsim
