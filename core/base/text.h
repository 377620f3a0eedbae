#pragma once
// Text helpers shared by the readers (names are matched case-insensitively, ASCII only).
#include <string>
#include <string_view>

namespace pmsim {

// ASCII lower case; other bytes (UTF-8 sequences) unchanged.
inline std::string lower_case(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

}  // namespace pmsim
