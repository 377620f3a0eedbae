#include "core/crystal/mineral_crystallography.h"

#include "core/base/json_reader.h"

namespace pmsim {

namespace {

const NameTable<CrystalSystem> kSystems = {{"cubic", CrystalSystem::Cubic},
                                           {"tetragonal", CrystalSystem::Tetragonal},
                                           {"hexagonal", CrystalSystem::Hexagonal},
                                           {"trigonal", CrystalSystem::Trigonal},
                                           {"orthorhombic", CrystalSystem::Orthorhombic},
                                           {"monoclinic", CrystalSystem::Monoclinic},
                                           {"triclinic", CrystalSystem::Triclinic}};
const NameTable<IndicatrixAxis> kAxes = {
    {"x", IndicatrixAxis::X}, {"y", IndicatrixAxis::Y}, {"z", IndicatrixAxis::Z}};
const NameTable<MonoclinicSide> kSides = {{"obtuse_beta", MonoclinicSide::ObtuseBeta},
                                          {"acute_beta", MonoclinicSide::AcuteBeta}};
const NameTable<CleavageQuality> kQualities = {
    {"perfect", CleavageQuality::Perfect}, {"very_good", CleavageQuality::VeryGood},
    {"good", CleavageQuality::Good},       {"distinct", CleavageQuality::Distinct},
    {"fair", CleavageQuality::Fair},       {"imperfect", CleavageQuality::Imperfect},
    {"poor", CleavageQuality::Poor},       {"parting", CleavageQuality::Parting}};

std::string source_of(const JsonReader& r) {
  const std::string s = r.require<std::string>("source");
  if (s.empty()) r.fail("source", "every block must cite the publication of its data");
  return s;
}

MillerIndices plane_at(const JsonReader& r, std::string_view key) {
  const std::string t = r.require<std::string>(key);
  return r.checked(key, *r.find(key), [&](const nlohmann::json&) { return parse_miller_plane(t); });
}
LatticeDirection direction_at(const JsonReader& r, std::string_view key) {
  const std::string t = r.require<std::string>(key);
  return r.checked(key, *r.find(key), [&](const nlohmann::json&) { return parse_lattice_direction(t); });
}

OpticalOrientation orientation_at(const JsonReader& o) {
  OpticalOrientation r;
  r.source = source_of(o);
  if (o.has("optic_axis")) {
    o.refuse_unknown_keys({"optic_axis", "source"});
    const std::string ax = o.require<std::string>("optic_axis");
    if (ax != "c") o.fail("optic_axis", "the optic axis of tetragonal, hexagonal and trigonal crystals is c");
    r.kind = OpticalOrientation::Kind::Uniaxial;
  } else if (o.has("inclined")) {
    o.refuse_unknown_keys({"b", "inclined", "source"});
    r.kind = OpticalOrientation::Kind::Monoclinic;
    r.along_b = o.require_enum("b", kAxes);
    const JsonReader in = o.object("inclined");
    in.refuse_unknown_keys({"axis", "from", "angle_deg", "side"});
    r.inclined = in.require_enum("axis", kAxes);
    const std::string from = in.require<std::string>("from");
    if (from != "c" && from != "a") in.fail("from", "expected c or a");
    r.from_a = from == "a";
    r.angle_deg = in.require<double>("angle_deg", Range::closed(0, 90));
    r.side = in.require_enum("side", kSides);
  } else if (o.has("normal_to")) {
    o.refuse_unknown_keys({"normal_to", "axis", "in_plane", "source"});
    r.kind = OpticalOrientation::Kind::Triclinic;
    r.normal_plane = plane_at(o, "normal_to");
    r.normal_axis = o.require_enum("axis", kAxes);
    const JsonReader in = o.object("in_plane");
    in.refuse_unknown_keys({"axis", "from", "angle_deg"});
    r.inclined = in.require_enum("axis", kAxes);
    r.reference_direction = direction_at(in, "from");
    r.angle_deg = in.require<double>("angle_deg", Range::open_closed(-90, 90));
  } else {
    o.refuse_unknown_keys({"a", "b", "c", "source"});
    r.kind = OpticalOrientation::Kind::Orthorhombic;
    r.along_a = o.require_enum("a", kAxes);
    r.along_b = o.require_enum("b", kAxes);
    r.along_c = o.require_enum("c", kAxes);
  }
  return r;
}

}  // namespace

std::optional<MineralCrystallography> read_mineral_crystallography(const JsonReader& root,
                                                                   CrystalSymmetry symmetry) {
  const bool any = root.has("crystal_system") || root.has("unit_cell") || root.has("optical_orientation") ||
                   root.has("cleavage") || root.has("habit") || root.has("twins");
  if (!any) return std::nullopt;
  MineralCrystallography m;
  m.system = root.require_enum("crystal_system", kSystems);
  {
    const JsonReader c = root.object("unit_cell");
    c.refuse_unknown_keys({"a", "b", "c", "alpha", "beta", "gamma", "source"});
    m.cell_source = source_of(c);
    m.cell.a_A = c.require<double>("a");
    m.cell.b_A = c.require<double>("b");
    m.cell.c_A = c.require<double>("c");
    m.cell.alpha_deg = c.require<double>("alpha");
    m.cell.beta_deg = c.require<double>("beta");
    m.cell.gamma_deg = c.require<double>("gamma");
    c.checked("", c.node(), [&](const nlohmann::json&) {
      check_unit_cell(m.system, m.cell);
      return 0;
    });
  }
  if (const auto o = root.optional_object("optical_orientation")) {
    m.orientation = orientation_at(*o);
    const bool uni = m.orientation->kind == OpticalOrientation::Kind::Uniaxial;
    if (symmetry == CrystalSymmetry::Isotropic)
      o->fail("", "an isotropic crystal has no optical orientation");
    if (uni != (symmetry == CrystalSymmetry::Uniaxial))
      o->fail("", uni ? "a biaxial crystal needs the orthorhombic, monoclinic or triclinic form"
                      : "a uniaxial crystal takes {\"optic_axis\": \"c\"}");
    m.indicatrix_axes = o->checked("", o->node(), [&](const nlohmann::json&) {
      return indicatrix_axes(m.system, m.cell, *m.orientation);
    });
  }
  if (root.has("cleavage")) {
    for (const JsonReader& c : root.objects("cleavage", 1)) {
      c.refuse_unknown_keys({"plane", "quality", "source"});
      m.cleavage.push_back({plane_at(c, "plane"), c.require_enum("quality", kQualities), source_of(c)});
    }
  }
  if (const auto h = root.optional_object("habit")) {
    h->refuse_unknown_keys({"elongation", "tabular", "source"});
    if (!h->has("elongation") && !h->has("tabular"))
      h->fail("", "a habit names an elongation [uvw], a tabular plane (hkl) or both");
    if (h->has("elongation")) m.habit.elongation = direction_at(*h, "elongation");
    if (h->has("tabular")) m.habit.tabular = plane_at(*h, "tabular");
    m.habit.source = source_of(*h);
  }
  if (root.has("twins")) {
    for (const JsonReader& t : root.objects("twins", 1)) {
      t.refuse_unknown_keys({"law", "plane", "source"});
      m.twins.push_back({t.require<std::string>("law"), plane_at(t, "plane"), source_of(t)});
    }
  }
  return m;
}

bool optical_orientation_is_stand_in(const MineralCrystallography* m, const Crystal& c) {
  return c.symmetry() != CrystalSymmetry::Isotropic && !(m && m->orientation);
}

}  // namespace pmsim
