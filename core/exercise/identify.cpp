#include "core/exercise/identify.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/base/input_error.h"
#include "core/exercise/exercise_kind.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

namespace {

constexpr double kOrderSlackNm = 60.0;
constexpr double kTwoVSlackDeg = 5.0;
constexpr double kExtinctionSlackDeg = 3.0;

// Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on literal + std::string.
void append(std::string& to, const char* sep, const std::string& piece) {
  if (!to.empty()) to += sep;
  to += piece;
}

std::string num(double v, int digits = 3) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

// Each test returns "" when the mineral is ruled out, else the reason it agrees.
std::string relief_reason(const MineralSignature& s, const Observations& o) {
  std::string why;
  if (o.relief) {
    if (!s.relief.count(*o.relief)) return "";
    why = std::string(relief_class_name(*o.relief)) + " relief (n " + num(s.n_min) + "–" + num(s.n_max) + ")";
  }
  if (o.relief_sign) {
    if (std::find(s.relief_signs.begin(), s.relief_signs.end(), *o.relief_sign) == s.relief_signs.end()) return "";
    append(why, "; ", *o.relief_sign + " relief against 1.54");
  }
  if (o.n_range) {
    if (s.n_max < (*o.n_range)[0] || s.n_min > (*o.n_range)[1]) return "";
    append(why, "; ", "n " + num(s.n_min) + "–" + num(s.n_max) + " meets " + num((*o.n_range)[0]) + "–" +
                          num((*o.n_range)[1]));
  }
  return why.empty() ? "-" : why;
}

std::string optics_reason(const MineralSignature& s, const Observations& o) {
  std::string why;
  const auto add = [&](const std::string& w) { append(why, "; ", w); };
  if (o.character) {
    if (*o.character != s.character) return "";
    add(s.character);
  }
  if (o.optic_sign) {
    if (*o.optic_sign != s.optic_sign) return "";
    add("optically " + s.optic_sign);
  }
  if (o.two_v_deg) {
    if (s.character == "isotropic" || s.two_v_deg < (*o.two_v_deg)[0] - kTwoVSlackDeg ||
        s.two_v_deg > (*o.two_v_deg)[1] + kTwoVSlackDeg)
      return "";
    add("2V " + num(s.two_v_deg, 0) + "°");
  }
  if (o.max_order) {
    const double gamma = 1000.0 * o.thickness_um * s.birefringence;
    const double lo = kOrderWavelengthNm * (*o.max_order - 1) - kOrderSlackNm, hi = kOrderWavelengthNm * *o.max_order + kOrderSlackNm;
    if (*o.max_order == 0 ? gamma > kOrderSlackNm : (gamma < lo || gamma > hi)) return "";
    add("birefringence " + num(s.birefringence, 4) + ": " + num(gamma, 0) + " nm at " + num(o.thickness_um, 0) +
        " µm, order " + std::to_string(max_interference_order(s.birefringence, o.thickness_um)));
  }
  return why.empty() ? "-" : why;
}

std::string look_reason(const MineralSignature& s, const Observations& o) {
  std::string why;
  const auto add = [&](const std::string& w) { append(why, "; ", w); };
  if (o.coloured) {
    if (*o.coloured != s.coloured) return "";
    add(s.coloured ? "coloured (" + num(s.colour_delta_e, 0) + " ΔE from white)" : "colourless");
  }
  if (o.pleochroic) {
    if (*o.pleochroic != s.pleochroic) return "";
    add(s.pleochroic ? "pleochroic (" + num(s.pleochroism_delta_e, 0) + " ΔE between axes)" : "not pleochroic");
  }
  if (o.cleavages) {
    if (std::size_t(*o.cleavages) > s.cleavages) return "";
    add(std::to_string(s.cleavages) + " cleavage plane" + (s.cleavages == 1 ? "" : "s") + " in the file");
  }
  if (o.twin_law) {
    const bool any = *o.twin_law == "any";
    const auto match = std::find_if(s.twin_laws.begin(), s.twin_laws.end(), [&](const std::string& law) {
      return any || answer_correct(TaskKind::TwinLaw, *o.twin_law, law.substr(0, law.find(' ')), std::nullopt) ||
             answer_correct(TaskKind::TwinLaw, *o.twin_law, law, std::nullopt);
    });
    if (match == s.twin_laws.end()) return "";
    add("twinned: " + *match);
  }
  return why.empty() ? "-" : why;
}

std::string extinction_reason(const MineralSignature& s, const Observations& o) {
  std::string why;
  const auto add = [&](const std::string& w) { append(why, "; ", w); };
  const bool known = s.extinction_max_deg.has_value();
  if (o.extinction_type && known) {
    if (!s.extinction_types.count(*o.extinction_type)) return "";
    add(*o.extinction_type + " extinction occurs to " + s.feature);
  }
  if (o.extinction_angle_deg && known) {
    if (*o.extinction_angle_deg > *s.extinction_max_deg + kExtinctionSlackDeg) return "";
    add("extinction angles 0–" + num(*s.extinction_max_deg, 0) + "° to " + s.feature);
  }
  if (o.elongation && known && !s.elongation_signs.empty()) {
    if (!s.elongation_signs.count(*o.elongation)) return "";
    add(*o.elongation);
  }
  if ((o.extinction_type || o.extinction_angle_deg || o.elongation) && !known)
    add("no extinction data (no optical orientation or feature in the file): not ruled out");
  return why.empty() ? "-" : why;
}

// Opacity first: it decides whether the other observations can apply at all.
std::string opaque_reason(const MineralSignature& s, const Observations& o) {
  if (!s.opaque) {
    if (o.opaque && *o.opaque) return "";
    return o.opaque ? "transparent in 30 µm" : "-";
  }
  if (o.opaque && !*o.opaque) return "";
  const bool transmitted = o.relief || o.relief_sign || o.n_range || o.coloured || o.pleochroic || o.max_order ||
                           o.character || o.optic_sign || o.two_v_deg || o.extinction_type ||
                           o.extinction_angle_deg || o.elongation;
  if (transmitted) return "";
  return o.opaque ? "opaque: black in plane and crossed light (under 1e-4 of the light through 30 µm)" : "-";
}

}  // namespace

std::vector<Candidate> identify(const Observations& o) {
  std::vector<Candidate> out;
  for (const MineralSignature& s : library_signatures()) {
    Candidate c{s.mineral, {}};
    bool ok = true;
    for (const auto& test : {opaque_reason, relief_reason, optics_reason, look_reason, extinction_reason}) {
      const std::string why = test(s, o);
      if (why.empty()) {
        ok = false;
        break;
      }
      if (why != "-") c.why.push_back(why);
    }
    if (ok) out.push_back(std::move(c));
  }
  return out;
}

Observations parse_observation(Observations o, const std::string& key, const std::string& value) {
  const auto bad = [&](const std::string& why) { return InputError("", key, value, why); };
  const auto word = [&](std::initializer_list<const char*> allowed) {
    for (const char* a : allowed)
      if (value == a) return value;
    std::string list;
    for (const char* a : allowed) append(list, "|", a);
    throw bad("expected " + list);
  };
  const auto number = [&](const std::string& t) {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end || !std::isfinite(v)) throw bad("expected a number");
    return v;
  };
  const auto range = [&]() {
    const auto colon = value.find(':');
    const double lo = number(value.substr(0, colon)), hi = colon == std::string::npos ? lo : number(value.substr(colon + 1));
    if (hi < lo) throw bad("expected LOW:HIGH with LOW ≤ HIGH");
    return std::array<double, 2>{lo, hi};
  };
  const auto yes_no = [&]() { return word({"yes", "no"}) == "yes"; };
  if (key == "opaque") o.opaque = yes_no();
  else if (key == "relief") {
    const std::string w = word({"low", "moderate", "high", "very_high"});
    o.relief = w == "low" ? ReliefClass::Low : w == "moderate" ? ReliefClass::Moderate : w == "high" ? ReliefClass::High : ReliefClass::VeryHigh;
  } else if (key == "relief-sign") o.relief_sign = word({"positive", "negative"});
  else if (key == "n") o.n_range = range();
  else if (key == "coloured") o.coloured = yes_no();
  else if (key == "pleochroic") o.pleochroic = yes_no();
  else if (key == "order") {
    const double v = number(value);
    if (v < 0 || v > 20 || v != std::floor(v)) throw bad("expected an order 0…20 (0: dark, isotropic)");
    o.max_order = int(v);
  } else if (key == "thickness") {
    o.thickness_um = number(value);
    if (!(o.thickness_um > 0 && o.thickness_um <= 1000)) throw bad("expected a thickness in (0, 1000] µm");
  } else if (key == "character") o.character = word({"isotropic", "uniaxial", "biaxial"});
  else if (key == "sign") o.optic_sign = word({"positive", "negative"});
  else if (key == "two-v") o.two_v_deg = range();
  else if (key == "extinction") o.extinction_type = word({"parallel", "inclined", "symmetric"});
  else if (key == "extinction-angle") o.extinction_angle_deg = number(value);
  else if (key == "elongation") o.elongation = word({"length-slow", "length-fast"});
  else if (key == "cleavages") {
    const double v = number(value);
    if (v < 0 || v > 6 || v != std::floor(v)) throw bad("expected 0…6 cleavage directions");
    o.cleavages = int(v);
  } else if (key == "twin") o.twin_law = value;
  else throw bad("not an observation");
  return o;
}

Observations observations_of(const MineralSignature& s) {
  Observations o;
  if (s.opaque) {
    // A black grain shows only that it is black, its outline and (in reflected light, or at its
    // edges) partings and twins: no relief, colour or interference to read.
    o.opaque = true;
    o.cleavages = 0;
    if (!s.twin_laws.empty()) o.twin_law = s.twin_laws.front();
    return o;
  }
  // What a student reads at the microscope: the relief class (not a measured index), 2V to
  // ±10°, the largest extinction angle seen.
  o.relief = relief_class(0.5 * (s.n_min + s.n_max));
  // An index equal to the medium's shows no Becke line to read a sign from (blue_epoxy, n 1.54).
  if (const double n = 0.5 * (s.n_min + s.n_max); n != kReliefMediumIndex)
    o.relief_sign = n > kReliefMediumIndex ? "positive" : "negative";
  o.coloured = s.coloured;
  o.pleochroic = s.pleochroic;
  o.max_order = max_interference_order(s.birefringence, 30.0);
  o.character = s.character;
  if (!s.optic_sign.empty()) o.optic_sign = s.optic_sign;
  if (s.character == "biaxial") o.two_v_deg = std::array<double, 2>{std::max(0.0, s.two_v_deg - 10.0), s.two_v_deg + 10.0};
  if (s.extinction_max_deg) {
    o.extinction_type = s.extinction_types.count("inclined") ? "inclined" : "parallel";
    o.extinction_angle_deg = *s.extinction_max_deg;
  }
  if (s.elongation_signs.size() == 1) o.elongation = *s.elongation_signs.begin();
  o.cleavages = int(s.cleavages);
  if (!s.twin_laws.empty()) o.twin_law = s.twin_laws.front();
  return o;
}

}  // namespace pmsim
