#pragma once
// A determinative aid (issue 23): what a student observed, against every library mineral's
// computed signature (mineral_signature.h); the consistent minerals, each with why.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/exercise/mineral_signature.h"

namespace pmsim {

struct Observations {
  std::optional<bool> opaque;               // black in plane and crossed light (magnetite, ilmenite)
  std::optional<ReliefClass> relief;        // relief class against n = 1.54
  std::optional<std::string> relief_sign;   // "positive" | "negative" (Becke line into / out of the grain)
  std::optional<std::array<double, 2>> n_range;  // an index measured in liquids, [lo, hi]
  std::optional<bool> coloured, pleochroic;
  std::optional<int> max_order;             // highest interference order seen …
  double thickness_um = 30.0;               // … at this thickness
  std::optional<std::string> character;     // "isotropic" | "uniaxial" | "biaxial"
  std::optional<std::string> optic_sign;
  std::optional<std::array<double, 2>> two_v_deg;  // [lo, hi]
  std::optional<std::string> extinction_type;      // "parallel" | "inclined" | "symmetric"
  std::optional<double> extinction_angle_deg;      // the largest measured
  std::optional<std::string> elongation;           // "length-slow" | "length-fast"
  std::optional<int> cleavages;                    // cleavage directions seen in one grain
  std::optional<std::string> twin_law;             // a law seen ("albite"), or "any"
};

struct Candidate {
  std::string mineral;
  std::vector<std::string> why;  // one line per observation it agrees with
};

// The minerals consistent with every observation given, in library order. An opaque mineral is
// consistent only with no transmitted-light observation (relief, colour, order, character, sign,
// 2V, extinction, elongation: none of them can be seen in a black grain) and opaque = yes or not
// given; a transparent one only without opaque = yes. Slack, each stated:
// an interference order may be misjudged by one near an order's end (±60 nm of retardation); 2V
// read ±5° beyond the range given; an extinction angle up to 3° beyond the largest the mineral
// shows in the sections that show its feature.
std::vector<Candidate> identify(const Observations& o);

// Throws InputError(key = the observation's name, value) for a word not in the observation's list.
Observations parse_observation(Observations o, const std::string& key, const std::string& value);
// The observations one mineral's signature gives a student who sees its most telling grain.
Observations observations_of(const MineralSignature& s);

}  // namespace pmsim
