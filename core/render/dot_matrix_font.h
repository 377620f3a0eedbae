#pragma once
// A 5 × 7 dot-matrix font for text burned into images (plot labels, scale bars): digits, upper-case
// letters, a few lower-case unit letters and punctuation. One glyph cell is 6 × 7 (a blank column).
#include <cstdint>

namespace pmsim {

struct DotMatrixGlyph {
  char c;
  std::uint8_t rows[7];  // top row first; bit 4 = leftmost column
};

// The glyph of c; lower-case letters without their own glyph fold to upper case; nullptr if none.
const DotMatrixGlyph* dot_matrix_glyph(char c);

}  // namespace pmsim
