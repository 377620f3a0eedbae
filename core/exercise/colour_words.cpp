#include "core/exercise/colour_words.h"

#include <algorithm>
#include <filesystem>

#include "core/base/asset_locator.h"
#include "core/base/json_reader.h"
#include "core/exercise/mineral_signature.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

namespace pmsim {

const std::vector<ColourWord>& colour_words() {
  static const std::vector<ColourWord> words = [] {
    const std::string path = (std::filesystem::path(asset_dir()) / "exercises" / "pleochroic_colours.json").string();
    const nlohmann::json j = read_json_file(path, "colour-word table");
    const JsonReader root(j, path);
    std::vector<ColourWord> out;
    const glm::dvec3 white = illuminant_white_xyz(Illuminant::D65);
    for (const JsonReader& c : root.objects("colours", 2)) {
      const nlohmann::json& rgb = c.node().at("srgb");
      glm::dvec3 lin;
      for (int k = 0; k < 3; ++k) {
        const double v = c.checked("srgb", rgb, [&](const nlohmann::json& a) { return number_value(a.at(std::size_t(k))); });
        if (!(v >= 0 && v <= 255)) c.fail("srgb", "expected three values 0-255");
        lin[k] = srgb_decode(v / 255.0);
      }
      // sRGB's white is D65: the table's white maps to L* = 100.
      out.push_back({c.require<std::string>("word"), xyz_to_lab(linear_srgb_to_xyz(lin) * white.y, white)});
    }
    return out;
  }();
  return words;
}

std::vector<std::string> nearest_colour_words(const glm::dvec3& lab) {
  std::vector<std::pair<double, std::string>> ranked;
  for (const ColourWord& w : colour_words()) ranked.emplace_back(ciede2000(lab, w.lab), w.word);
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (auto& r : ranked) out.push_back(std::move(r.second));
  return out;
}

std::string pleochroism_words(const std::string& mineral, double thickness_um) {
  const auto lab = principal_colours_lab(mineral, thickness_um);
  std::string s;
  for (int a = 0; a < 3; ++a) {
    if (a) s += ", ";
    s += nearest_colour_words(lab[std::size_t(a)]).front();
  }
  return s;
}

}  // namespace pmsim
