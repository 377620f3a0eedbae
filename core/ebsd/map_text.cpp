#include "core/ebsd/map_text.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

namespace pmsim {

MapText::MapText(std::string path) : path_(std::move(path)) {
  // One read of the whole file: a 10⁶-point map is ~70 MB of text, read in well under a second;
  // std::FILE keeps it to a single buffer (no stream buffering on top).
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path_.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(path_, "", "", "cannot open the map file");
  if (std::fseek(f.get(), 0, SEEK_END) != 0) throw InputError(path_, "", "", "cannot read the map file");
  const long size = std::ftell(f.get());
  if (size < 0) throw InputError(path_, "", "", "cannot read the map file (is it a folder?)");
  std::rewind(f.get());
  text_.resize(static_cast<std::size_t>(size));
  if (size > 0 && std::fread(text_.data(), 1, text_.size(), f.get()) != text_.size())
    throw InputError(path_, "", "", "cannot read the map file");
  // A UTF-8 byte-order mark (written by some Windows editors) is not part of the first key.
  if (text_.size() >= 3 && text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
}

bool MapText::next_line(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const char* base = text_.data();
  const void* nl = std::memchr(base + pos_, '\n', text_.size() - pos_);
  const std::size_t end = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - base) : text_.size();
  std::string_view l(base + pos_, end - pos_);
  while (!l.empty() && is_blank(l.back())) l.remove_suffix(1);
  line = l;
  pos_ = end + 1;
  ++line_no_;
  return true;
}

void MapText::fail(std::string_view field, std::string_view value, const std::string& why) const {
  throw InputError(path_, "line " + std::to_string(line_no_) + ": " + std::string(field), std::string(value),
                   why);
}

void MapText::fail_header(std::string_view field, const std::string& why) const {
  throw InputError(path_, std::string(field), "",
                   why + " (the header ended at line " + std::to_string(line_no_) + ")");
}

double MapText::to_double(std::string_view token, std::string_view field) const {
  double v = 0.0;
  if (!parse_number(token, v) || !std::isfinite(v)) fail(field, token, "not a number");
  return v;
}

float MapText::to_float(std::string_view token, std::string_view field) const {
  float v = 0.0f;
  if (!parse_number(token, v) || !std::isfinite(v)) fail(field, token, "not a number");
  return v;
}

long MapText::to_integer(std::string_view token, std::string_view field) const {
  long v = 0;
  if (!parse_number(token, v)) fail(field, token, "not an integer");
  return v;
}

}  // namespace pmsim
