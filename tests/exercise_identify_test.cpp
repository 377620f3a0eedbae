// pmsim-exercise identify (issue 23): every library mineral, described by what a student reads of
// its own computed signature (relief class, colour, highest order at 30 µm, character, sign, 2V to
// ±10°, extinction, elongation, cleavages, twins), is among the candidates, and the list is short.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "core/base/input_error.h"
#include "core/exercise/identify.h"

using namespace pmsim;

namespace {
bool lists(const std::vector<Candidate>& c, const std::string& m) {
  return std::any_of(c.begin(), c.end(), [&](const Candidate& x) { return x.mineral == m; });
}
}  // namespace

// "Short": at most 3 of the 59 library materials and 1.5 on average. Measured: 3 and 1.32 (1.33 of
// 58 before aqueous_fluid, alone in its list at n 1.333; 1.34 of
// 56 before glass and blue_epoxy; 1.35 of 54 before the opaque magnetite and ilmenite, each
// alone in its list by its twin law; blue_epoxy, at the medium's index, shows no relief sign) — the three
// garnet-like isotropic minerals of high relief (grossular, pyrope, spinel) and the colourless
// biaxial positive minerals of moderate relief and 2V near 60-70° (clinozoisite, enstatite, jadeite,
// topaz) are not told apart by these observations, as in a real determinative table; a measured
// index (--n) separates them. The test can fail: without the order and character observations
// (PMSIM_IDENTIFY_WEAKEN=1) the longest list is 18 and the mean 2.74.
TEST(Identify, EveryMineralFindsItselfInAShortList) {
  std::size_t longest = 0, total = 0;
  for (const MineralSignature& s : library_signatures()) {
    Observations o = observations_of(s);
    if (std::getenv("PMSIM_IDENTIFY_WEAKEN")) o.max_order.reset(), o.character.reset();
    const auto c = identify(o);
    EXPECT_TRUE(lists(c, s.mineral)) << s.mineral;
    for (const Candidate& x : c) EXPECT_FALSE(x.why.empty()) << x.mineral << ": a candidate says why";
    longest = std::max(longest, c.size());
    total += c.size();
  }
  std::printf("longest list %zu, mean %.2f over %zu minerals\n", longest, double(total) / double(library_signatures().size()),
              library_signatures().size());
  EXPECT_LE(longest, 3u);
  EXPECT_LE(double(total) / double(library_signatures().size()), 1.5);
}

// The signatures are computed from the data: textbook values (Nesse 2012) come out.
TEST(Identify, SignaturesAgreeWithTheTables) {
  const MineralSignature q = mineral_signature("quartz"), b = mineral_signature("biotite"),
                         a = mineral_signature("augite"), e = mineral_signature("enstatite");
  EXPECT_EQ(q.character, "uniaxial");
  EXPECT_EQ(q.optic_sign, "positive");
  EXPECT_EQ(max_interference_order(q.birefringence, 30), 1);  // δ 0.009: 270 nm, first-order white
  EXPECT_FALSE(q.coloured);
  EXPECT_TRUE(b.coloured && b.pleochroic);
  EXPECT_TRUE(b.relief.count(ReliefClass::Moderate));
  // Orthopyroxene: parallel extinction to its prism in every section of the [001] zone (max ≤ 3°);
  // augite: inclined, up to Z∧c (Nesse: 35–48°), and symmetric on its basal section ({110} at 87°).
  ASSERT_TRUE(e.extinction_max_deg && a.extinction_max_deg);
  EXPECT_LE(*e.extinction_max_deg, 3.0);
  EXPECT_EQ(e.extinction_types.count("inclined"), 0u);
  EXPECT_TRUE(e.extinction_types.count("symmetric")) << "the basal section bisects the {210} cleavages";
  EXPECT_GE(*a.extinction_max_deg, 35.0);
  EXPECT_LE(*a.extinction_max_deg, 48.0);
  EXPECT_TRUE(a.extinction_types.count("inclined") && a.extinction_types.count("symmetric"));
}

TEST(Identify, ObservationsRuleOutAndParse) {
  Observations o;
  o = parse_observation(o, "character", "isotropic");
  o = parse_observation(o, "order", "2");
  EXPECT_TRUE(identify(o).empty()) << "an isotropic mineral shows no interference colour";
  Observations g;
  g = parse_observation(g, "character", "uniaxial");
  g = parse_observation(g, "sign", "positive");
  g = parse_observation(g, "order", "1");
  g = parse_observation(g, "relief", "low");
  g = parse_observation(g, "coloured", "no");
  const auto c = identify(g);
  EXPECT_TRUE(lists(c, "quartz"));
  EXPECT_FALSE(lists(c, "calcite"));
  try {
    parse_observation(g, "relief", "medium");
    FAIL();
  } catch (const InputError& err) {
    EXPECT_EQ(err.key, "relief");
    EXPECT_EQ(err.value, "medium");
  }
  EXPECT_THROW(parse_observation(g, "two-v", "60:20"), InputError);
  EXPECT_THROW(parse_observation(g, "colour", "yes"), InputError);
}
