#pragma once
// The text of a map file and the line-by-line reading both readers share: the whole file in one
// buffer, lines as string_views into it (no allocation per line), CR LF and trailing blanks
// stripped, numbers parsed with std::from_chars (locale-free, exact round trip), and every
// refusal an InputError naming the file, the line and the field.
#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>

#include "core/base/input_error.h"

namespace pmsim {

class MapText {
 public:
  // Reads the whole file; InputError naming it when it cannot be read.
  explicit MapText(std::string path);

  const std::string& path() const { return path_; }
  // The next line (without its end and trailing blanks) and its 1-based number; false at the end.
  bool next_line(std::string_view& line);
  std::size_t line_number() const { return line_no_; }
  bool at_end() const { return pos_ >= text_.size(); }

  // InputError for the current line: key "line N: <field>", the offending text, the reason.
  [[noreturn]] void fail(std::string_view field, std::string_view value, const std::string& why) const;
  // Header-level refusal (a missing key): key "<field>" with the line the header ended on.
  [[noreturn]] void fail_header(std::string_view field, const std::string& why) const;

  double to_double(std::string_view token, std::string_view field) const;
  float to_float(std::string_view token, std::string_view field) const;
  long to_integer(std::string_view token, std::string_view field) const;

 private:
  std::string path_;
  std::string text_;
  std::size_t pos_ = 0;
  std::size_t line_no_ = 0;
};

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

inline std::string_view trimmed(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

// The next field of `rest` separated by blanks (tabs or spaces, runs count as one); "" at the end.
inline std::string_view next_field(std::string_view& rest) {
  std::size_t i = 0;
  while (i < rest.size() && is_blank(rest[i])) ++i;
  std::size_t j = i;
  while (j < rest.size() && !is_blank(rest[j])) ++j;
  std::string_view f = rest.substr(i, j - i);
  rest.remove_prefix(j);
  return f;
}

// The next field of `rest` up to a tab (blanks inside kept, the field trimmed); "" at the end.
inline std::string_view next_tab_field(std::string_view& rest) {
  const std::size_t t = rest.find('\t');
  std::string_view f = rest.substr(0, t);
  rest.remove_prefix(t == std::string_view::npos ? rest.size() : t + 1);
  return trimmed(f);
}

// A number, the whole token; false when it is not one. A leading '+' is accepted (from_chars
// refuses it; some writers emit it).
template <class T>
inline bool parse_number(std::string_view token, T& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto r = std::from_chars(token.data(), token.data() + token.size(), out);
  return r.ec == std::errc() && r.ptr == token.data() + token.size();
}

}  // namespace pmsim
