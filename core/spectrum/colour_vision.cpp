#include "core/spectrum/colour_vision.h"

#include <array>

namespace pmsim {
namespace {

struct VisionRow {
  ColourVision vision;
  std::string_view name;
  double m[3][3];  // rows of Φ as printed in Machado (2010), severity 1.0
};

// Machado (2010), tables of Φ_CVD for severity 1.0 (protanomaly, deuteranomaly and tritanomaly at
// full severity), as also distributed with colour-science's CVD_MATRICES_MACHADO2010.
constexpr std::array<VisionRow, 4> kVisions = {{
    {ColourVision::Normal, "normal", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
    {ColourVision::Protanopia,
     "protanopia",
     {{0.152286, 1.052583, -0.204868}, {0.114503, 0.786281, 0.099216}, {-0.003882, -0.048116, 1.051998}}},
    {ColourVision::Deuteranopia,
     "deuteranopia",
     {{0.367322, 0.860646, -0.227968}, {0.280085, 0.672501, 0.047413}, {-0.011820, 0.042940, 0.968881}}},
    {ColourVision::Tritanopia,
     "tritanopia",
     {{1.255528, -0.076749, -0.178779}, {-0.078411, 0.930809, 0.147602}, {0.004733, 0.691367, 0.303900}}},
}};

}  // namespace

glm::dmat3 colour_vision_matrix(ColourVision v) {
  for (const VisionRow& r : kVisions)
    if (r.vision == v) {
      glm::dmat3 m(1.0);
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) m[col][row] = r.m[row][col];  // glm is column-major
      return m;
    }
  return glm::dmat3(1.0);
}

std::string_view colour_vision_name(ColourVision v) {
  for (const VisionRow& r : kVisions)
    if (r.vision == v) return r.name;
  return "normal";
}

bool parse_colour_vision(std::string_view name, ColourVision& v) {
  for (const VisionRow& r : kVisions)
    if (r.name == name) {
      v = r.vision;
      return true;
    }
  return false;
}

}  // namespace pmsim
