#pragma once
// Names for the colours of pleochroism (assets/exercises/pleochroic_colours.json): a word per
// reference colour, the nearest in CIEDE2000 names an axis's colour, and an answer is accepted
// when the word given is the nearest or the second nearest (neighbouring words of a descriptive
// scale, "pale brown" for "yellow-brown", are what two observers differ by).
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace pmsim {

struct ColourWord {
  std::string word;
  glm::dvec3 lab;  // CIELAB, D65 white, from the table's sRGB
};

const std::vector<ColourWord>& colour_words();  // the table, loaded once; InputError naming the file
// The words ranked by CIEDE2000 from `lab`, nearest first.
std::vector<std::string> nearest_colour_words(const glm::dvec3& lab);
// "pale yellow, dark brown, dark brown": the words of X, Y, Z.
std::string pleochroism_words(const std::string& mineral, double thickness_um = 30.0);

}  // namespace pmsim
