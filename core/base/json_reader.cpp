#include "core/base/json_reader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/base/text.h"

namespace pmsim {

using nlohmann::json;

std::string shown(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

std::string number_text(double v) {
  char buf[64];
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::message() const {
  if (hi >= 1e308) return std::string(lo_open ? "must be > " : "must be ≥ ") + number_text(lo);
  if (lo <= -1e308) return std::string(hi_open ? "must be < " : "must be ≤ ") + number_text(hi);
  return std::string("must be in ") + (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) +
         (hi_open ? ")" : "]");
}

double number_value(const json& v) {
  if (!v.is_number()) throw BadValue{"expected a number"};
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw BadValue{"not a finite number"};
  return d;
}

int integer_value(const json& v) {
  const double d = number_value(v);
  // The whole int range: sample.orientation_seed takes seeds up to 2^31 - 1 (a class exercise's).
  if (d != std::floor(d) || d > 2147483647.0 || d < -2147483648.0) throw BadValue{"expected an integer"};
  return static_cast<int>(d);
}

bool bool_value(const json& v) {
  if (!v.is_boolean()) throw BadValue{"expected true or false"};
  return v.get<bool>();
}

namespace {
// Well-formed UTF-8 (RFC 3629: no overlongs, no surrogates, ≤ U+10FFFF): anything else cannot be
// saved back as JSON (nlohmann's dump throws on it).
bool valid_utf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    int n;
    unsigned cp;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      n = 1, cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2, cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3, cp = c & 0x07;
    } else {
      return false;
    }
    if (i + n >= s.size()) return false;  // truncated sequence
    for (int k = 1; k <= n; ++k) {
      const unsigned char d = static_cast<unsigned char>(s[i + k]);
      if ((d & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    static constexpr unsigned kMin[4] = {0, 0x80, 0x800, 0x10000};
    if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n + 1;
  }
  return true;
}
}  // namespace

std::string string_value(const json& v) {
  if (!v.is_string()) throw BadValue{"expected a string"};
  std::string s = v.get<std::string>();
  if (!valid_utf8(s)) throw BadValue{"not valid UTF-8 text"};
  return s;
}

std::string lower_string_value(const json& v) { return lower_case(string_value(v)); }

std::array<double, 3> vector3_value(const json& v) {
  if (!v.is_array() || v.size() != 3) throw BadValue{"expected a vector [x, y, z]"};
  std::array<double, 3> a{};
  for (int i = 0; i < 3; ++i) a[i] = number_value(v[i]);
  return a;
}

std::array<double, 3> unit_vector_value(const json& v) {
  std::array<double, 3> a = vector3_value(v);
  const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(len > 1e-12)) throw BadValue{"a direction cannot be the zero vector"};
  if (std::abs(len - 1.0) > 4.0 * std::numeric_limits<double>::epsilon())
    for (double& c : a) c /= len;
  return a;
}

std::string read_text_file(const std::string& path, const std::string& what) {
  // A folder opens as an ifstream on Linux and fails only while being read, from inside the
  // parser (std::ios_base::failure thrown through nlohmann's lexer left its heap corrupt): refuse
  // it here and parse from memory.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path, "", "", "cannot read: is a folder, not a " + what);
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "", "", "cannot open the " + what);
  std::ostringstream text;
  text << f.rdbuf();
  if (f.bad()) throw InputError(path, "", "", "cannot read the " + what);
  return text.str();
}

json read_json_file(const std::string& path, const std::string& what) {
  const std::string text = read_text_file(path, what);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double (1e400)
    throw InputError(path, "", "", std::string("not valid JSON: ") + e.what());
  }
}

JsonReader::JsonReader(const json& j, std::string file, std::string prefix,
                       std::vector<std::string>* warnings)
    : j_(&j), file_(std::move(file)), prefix_(std::move(prefix)), warnings_(warnings) {}

std::string JsonReader::path(std::string_view key) const {
  if (prefix_.empty()) return std::string(key);
  if (key.empty()) return prefix_;
  return prefix_ + "." + std::string(key);
}

const json* JsonReader::find(std::string_view key) const {
  const json* at = j_;
  while (true) {
    if (!at->is_object()) return nullptr;
    const std::size_t dot = key.find('.');
    const auto it = at->find(std::string(key.substr(0, dot)));
    if (it == at->end()) return nullptr;
    if (dot == std::string_view::npos) return &*it;
    at = &*it;
    key.remove_prefix(dot + 1);
  }
}

const json& JsonReader::required(std::string_view key) const {
  const json* v = find(key);
  if (!v) throw InputError(file_, path(key), "", "missing required key");
  return *v;
}

std::array<double, 3> JsonReader::require_unit_vector(std::string_view key) const {
  return checked(key, required(key), unit_vector_value);
}

std::optional<std::array<double, 3>> JsonReader::optional_unit_vector(std::string_view key) const {
  const json* v = find(key);
  if (!v) return std::nullopt;
  return checked(key, *v, unit_vector_value);
}

JsonReader JsonReader::object(std::string_view key) const {
  const json& v = required(key);
  if (!v.is_object()) fail(key, v, "expected an object");
  return JsonReader(v, file_, path(key), warnings_);
}

std::optional<JsonReader> JsonReader::optional_object(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return object(key);
}

std::vector<JsonReader> JsonReader::objects(std::string_view key, std::size_t min_size) const {
  const json& v = required(key);
  const std::string why = min_size > 0
                              ? "expected an array of at least " + std::to_string(min_size) + " objects"
                              : "expected an array of objects";
  if (!v.is_array() || v.size() < min_size) fail(key, v, why);
  std::vector<JsonReader> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string p = path(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_object()) throw InputError(file_, p, shown(v[i]), "expected an object");
    out.emplace_back(v[i], file_, p, warnings_);
  }
  return out;
}

std::vector<std::string> JsonReader::unknown_keys(std::initializer_list<std::string_view> known) const {
  std::vector<std::string> out;
  if (!j_->is_object()) return out;
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    bool k = false;
    for (std::string_view n : known) k = k || it.key() == n;
    if (!k) out.push_back(it.key());
  }
  return out;
}

void JsonReader::warn(const std::string& message) const {
  if (warnings_) warnings_->push_back((file_.empty() ? "" : file_ + ": ") + message);
}

void JsonReader::warn_unknown_keys(std::initializer_list<std::string_view> known) const {
  for (const std::string& k : unknown_keys(known)) warn("unknown key '" + path(k) + "' ignored");
}

void JsonReader::refuse_unknown_keys(std::initializer_list<std::string_view> known) const {
  for (const std::string& k : unknown_keys(known)) fail(k, j_->at(k), "unknown key");
}

void JsonReader::fail(std::string_view key, const json& value, const std::string& why) const {
  throw InputError(file_, path(key), value.is_null() ? "null" : shown(value), why);
}

void JsonReader::fail(std::string_view key, const std::string& why) const {
  const json* v = find(key);
  throw InputError(file_, path(key), v ? shown(*v) : "", why);
}

}  // namespace pmsim
