#pragma once
// How the image looks to an observer with a colour-vision deficiency (render.vision), so that a
// teacher can see which interference colours a protanope, deuteranope or tritanope student cannot
// tell apart. Machado, Oliveira & Fernandes (2009), "A physiologically-based model for simulation
// of color vision deficiency", IEEE TVCG 15(6) 1291–1298: a matrix Φ on linear sRGB per
// deficiency; the severity-1.0 matrices of Machado's tables (G. M. Machado 2010, MSc thesis,
// UFRGS, http://www.lume.ufrgs.br/handle/10183/26950) — dichromacy for protans and deuterans (Φ
// of rank 2: their colours lie in a plane), the model's strongest tritanomaly for tritans.
#include <string>
#include <string_view>

#include <glm/mat3x3.hpp>

namespace pmsim {

enum class ColourVision { Normal, Protanopia, Deuteranopia, Tritanopia };

// Φ for linear sRGB column vectors (rgb' = Φ·rgb); the identity for Normal.
glm::dmat3 colour_vision_matrix(ColourVision v);

// render.vision names: normal | protanopia | deuteranopia | tritanopia.
std::string_view colour_vision_name(ColourVision v);
bool parse_colour_vision(std::string_view name, ColourVision& v);

}  // namespace pmsim
