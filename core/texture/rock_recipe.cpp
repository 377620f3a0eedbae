#include "core/texture/rock_recipe.h"

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/base/asset_locator.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/mineral_series.h"

namespace pmsim {

namespace {

void known_mineral(const JsonReader& r, const char* key, const std::string& name) {
  try {
    (void)find_mineral(name);
  } catch (const InputError& e) {
    r.fail(key, e.what());
  }
}

}  // namespace

HaloRecipe read_halo(const JsonReader& h, double size_mm, double spacing_mm, double trail_spacing_mm) {
  h.warn_unknown_keys({"radius_mm", "darkening"});
  HaloRecipe r;
  r.radius_mm = h.require<double>("radius_mm", Range::open_closed(0.5 * size_mm, std::min(spacing_mm, trail_spacing_mm)));
  r.darkening = h.require<double>("darkening", Range::open_closed(1.0, HaloRecipe::kMaxDarkening));
  return r;
}

const char* inclusion_habit_name(InclusionHabit h) {
  return h == InclusionHabit::Needle ? "needle" : h == InclusionHabit::Wedge ? "wedge" : "trail";
}

InclusionHabit read_inclusion_habit(const JsonReader& a, const std::string& mineral, double size_mm,
                                    double trail_spacing_mm) {
  const std::string habit = a.get_or<std::string>("habit", "trail");
  if (habit == "trail") return InclusionHabit::Trail;
  if (habit == "wedge") return InclusionHabit::Wedge;
  if (habit != "needle") a.fail("habit", "expected \"trail\", \"needle\" or \"wedge\"");
  const MineralCrystallography* mc = find_mineral_crystallography(mineral);
  if (!mc || !mc->habit.elongation || !mc->orientation)
    a.fail("habit", "a needle grows along its mineral's elongation, and " + mineral +
                        " has no habit.elongation and optical_orientation in the library");
  if (size_mm > trail_spacing_mm)
    a.fail("habit", "a needle " + std::to_string(size_mm) + " mm long lies any way: it needs trail_spacing_mm >= size_mm (" +
                        std::to_string(trail_spacing_mm) + ")");
  return InclusionHabit::Needle;
}

namespace {

InclusionRecipe read_inclusions(const JsonReader& a) {
  using L = InclusionRecipe;
  a.warn_unknown_keys({"mineral", "size_mm", "aspect", "spacing_mm", "trail_spacing_mm", "fraction", "within",
                       "trail_deg", "rotation_deg", "orientations", "halo", "habit"});
  InclusionRecipe in;
  in.mineral = a.require<std::string>("mineral");
  known_mineral(a, "mineral", in.mineral);
  in.size_mm = a.require<double>("size_mm", Range::open_closed(0, L::kMaxSizeMm));
  in.aspect = a.get_or("aspect", 1.0, Range::closed(1, L::kMaxAspect));
  in.spacing_mm = a.require<double>("spacing_mm", Range::closed(in.size_mm, L::kMaxSpacingMm));
  in.trail_spacing_mm =
      a.get_or("trail_spacing_mm", in.spacing_mm, Range::closed(in.size_mm / in.aspect, L::kMaxSpacingMm));
  in.fraction = a.get_or("fraction", 1.0, Range::closed(0, 1));
  in.within = a.get_or("within", 1.0, Range::open_closed(0, 1));
  in.trail_deg = a.optional<double>("trail_deg", Range::closed(-L::kMaxTrailDeg, L::kMaxTrailDeg));
  in.rotation_deg = a.get_or("rotation_deg", 0.0, Range::closed(-L::kMaxRotationDeg, L::kMaxRotationDeg));
  in.orientations = a.get_or("orientations", 4, Range::closed(1, L::kMaxOrientations));
  in.habit = read_inclusion_habit(a, in.mineral, in.size_mm, in.trail_spacing_mm);
  if (const auto h = a.optional_object("halo")) in.halo = read_halo(*h, in.size_mm, in.spacing_mm, in.trail_spacing_mm);
  return in;
}

MyrmekiteRecipe read_myrmekite(const JsonReader& m) {
  using L = MyrmekiteRecipe;
  m.warn_unknown_keys({"host", "depth_mm", "bulb_mm", "fraction", "quartz", "source"});
  MyrmekiteRecipe r;
  r.host = m.require<std::string>("host");
  known_mineral(m, "host", r.host);
  r.depth_mm = m.require<double>("depth_mm", Range::open_closed(0, L::kMaxDepthMm));
  r.bulb_mm = m.require<double>("bulb_mm", Range::open_closed(0, L::kMaxBulbMm));
  r.fraction = m.get_or("fraction", 1.0, Range::closed(0, 1));
  const JsonReader q = m.object("quartz");
  q.warn_unknown_keys({"mineral", "width_mm", "spacing_mm"});
  r.quartz_mineral = q.get_or<std::string>("mineral", "quartz");
  known_mineral(q, "mineral", r.quartz_mineral);
  r.rod_width_mm = q.require<double>("width_mm", Range::open_closed(0, L::kMaxRodWidthMm));
  r.rod_spacing_mm = q.require<double>("spacing_mm", Range::closed(r.rod_width_mm, L::kMaxRodSpacingMm));
  return r;
}

const NameTable<CsdRecipe::Law> kCsdLaws = {{"log-linear", CsdRecipe::Law::log_linear},
                                            {"log-normal", CsdRecipe::Law::log_normal}};

CsdRecipe read_csd(const JsonReader& c) {
  c.warn_unknown_keys({"law", "slope_per_mm", "median_mm", "sorting_phi", "min_mm", "max_mm", "source"});
  CsdRecipe csd;
  csd.law = c.optional_enum("law", kCsdLaws).value_or(CsdRecipe::Law::log_linear);
  csd.min_mm = c.require<double>("min_mm", Range::above(0));
  csd.max_mm = c.require<double>("max_mm", Range::above(0));
  if (!(csd.max_mm > csd.min_mm)) c.fail("max_mm", "the size range is empty (max_mm must exceed min_mm)");
  if (csd.law == CsdRecipe::Law::log_linear) {
    csd.slope_per_mm = c.require<double>("slope_per_mm", Range::open(-1e6, 0));
    return csd;
  }
  if (c.has("slope_per_mm")) c.fail("slope_per_mm", "a log-normal size law has a median and a sorting, not a slope");
  csd.median_mm = c.require<double>("median_mm", Range::closed(csd.min_mm, csd.max_mm));
  // Beyond 4 φ a "sorting" spans more than the sand grades (Folk & Ward 1957: over 4 is
  // extremely poorly sorted); under 0.05 it is one size.
  csd.sorting_phi = c.require<double>("sorting_phi", Range::closed(0.05, 4.0));
  return csd;
}

PhaseRecipe read_phase(const JsonReader& pr, bool granoblastic) {
  pr.warn_unknown_keys({"name", "mineral", "mode_percent", "csd", "nucleation", "aspect", "zoning", "twin", "fabric", "undulose", "shape", "porphyroblast", "alteration", "inclusions", "overgrowth", "myrmekite", "source"});
  PhaseRecipe p;
  p.mineral = pr.require<std::string>("mineral");
  known_mineral(pr, "mineral", p.mineral);
  p.name = pr.get_or<std::string>("name", p.mineral);
  p.mode_percent = pr.require<double>("mode_percent", Range::open_closed(0, 100));
  if (granoblastic) {
    if (pr.has("csd")) pr.fail("csd", "a granoblastic rock's grains take their size from \"granoblastic\".grain_mm");
  } else {
    p.csd = read_csd(pr.object("csd"));
  }
  p.nucleation = pr.get_or("nucleation", 0.0, Range::closed(0, 0.99));
  p.aspect = pr.optional<double>("aspect", Range::at_least(1));
  const std::string shape = pr.get_or<std::string>("shape", "habit");
  if (shape != "habit" && shape != "rounded") pr.fail("shape", "expected \"habit\" or \"rounded\"");
  p.rounded = shape == "rounded";
  if (p.rounded && granoblastic) pr.fail("shape", "a granoblastic rock's grains are shaped by their neighbours");
  if (p.rounded && p.aspect) pr.fail("aspect", "a rounded grain is a ball: it has no aspect");
  if (p.rounded && pr.has("fabric")) pr.fail("fabric", "a rounded grain (a ball) has no axis to align");
  p.porphyroblast = pr.get_or("porphyroblast", false);
  if (p.porphyroblast && granoblastic) pr.fail("porphyroblast", "a granoblastic rock's grains recrystallised together");
  if (const auto z = pr.optional_object("zoning")) {
    ZoningRecipe zr;
    const std::string kind = z->require<std::string>("kind");
    if (kind != "oscillatory" && kind != "normal") z->fail("kind", "expected \"oscillatory\" or \"normal\"");
    if (p.mineral.find(':') == std::string::npos)
      pr.fail("zoning", "zoning needs a mineral with a composition (\"plagioclase:An55\")");
    zr.oscillatory = kind == "oscillatory";
    zr.core = z->require<double>("core", Range::closed(0, 100));
    zr.rim = z->require<double>("rim", Range::closed(0, 100));
    zr.amplitude = z->get_or("amplitude", 0.0, Range::closed(0, 50));
    zr.bands = z->get_or("bands", 4, Range::closed(1, 64));
    p.zoning = zr;
  }
  if (const auto t = pr.optional_object("twin")) {
    TwinRecipe tr;
    tr.law = t->require<std::string>("law");
    tr.lamella_mm = t->get_or("lamella_mm", 0.0, Range::at_least(0));
    tr.fraction = t->get_or("fraction", 1.0, Range::closed(0, 1));
    if (const auto x = t->optional_object("cross")) {
      x->warn_unknown_keys({"law", "lamella_mm"});
      tr.cross_law = x->require<std::string>("law");
      tr.cross_lamella_mm = x->require<double>("lamella_mm", Range::above(0));
      if (!(tr.lamella_mm > 0.0)) t->fail("lamella_mm", "a cross-hatched twin crosses lamellae: the first set needs lamella_mm > 0 too");
    }
    p.twin = tr;
  }
  if (const auto f = pr.optional_object("fabric")) {
    FabricRecipe fr;
    const std::string align = f->require<std::string>("align");
    if (align != "elongation" && align != "plate_normal") f->fail("align", "expected \"elongation\" or \"plate_normal\"");
    const MineralCrystallography* mc = find_mineral_crystallography(p.mineral);
    if (!mc || (align == "elongation" ? !mc->habit.elongation : !mc->habit.tabular))
      f->fail("align", "the mineral file gives no " + std::string(align == "elongation" ? "elongation" : "tabular plane") +
                           " to align");
    fr.plate_normal = align == "plate_normal";
    fr.direction = f->require_unit_vector("direction");
    fr.spread_deg = f->get_or("spread_deg", 15.0, Range::closed(0, 90));
    p.fabric = fr;
  }
  if (const auto u = pr.optional_object("undulose")) {
    UnduloseRecipe ur;
    ur.subgrain_mm = u->require<double>("subgrain_mm", Range::above(0));
    ur.step_deg = u->require<double>("step_deg", Range::open_closed(0, 15));
    p.undulose = ur;
  }
  if (const auto a = pr.optional_object("alteration")) {
    AlterationRecipe ar;
    ar.mineral = a->require<std::string>("mineral");
    known_mineral(*a, "mineral", ar.mineral);
    ar.vein_mm = a->require<double>("vein_mm", Range::open_closed(0, 1));
    ar.fraction = a->get_or("fraction", 1.0, Range::closed(0, 1));
    const std::string orientation = a->get_or<std::string>("orientation", "random");
    if (orientation != "random" && orientation != "host") a->fail("orientation", "expected \"random\" or \"host\"");
    ar.host_orientation = orientation == "host";
    p.alteration = ar;
  }
  if (const auto a = pr.optional_object("inclusions")) {
    p.inclusions = read_inclusions(*a);
    if (p.inclusions->halo && !find_mineral(p.mineral).absorbing())
      a->fail("halo", "a pleochroic halo darkens its host's absorption, and " + p.mineral +
                          " has no absorption data: it would not show");
  }
  if (const auto o = pr.optional_object("overgrowth")) {
    o->warn_unknown_keys({"cement_percent", "dust", "source"});
    if (!p.rounded) pr.fail("overgrowth", "an overgrowth grows on a rounded detrital grain (\"shape\": \"rounded\")");
    const MineralCrystallography* mc = find_mineral_crystallography(p.mineral);
    if (!mc) pr.fail("overgrowth", "an overgrowth continues its grain's lattice, and " + p.mineral + " has no unit cell in the library");
    OvergrowthRecipe og;
    og.cement_percent = o->require<double>("cement_percent", Range::open_closed(0, 100));
    if (const auto d = o->optional_object("dust")) {
      d->warn_unknown_keys({"mineral", "size_mm", "spacing_mm", "fraction"});
      DustLineRecipe dust;
      dust.mineral = d->require<std::string>("mineral");
      known_mineral(*d, "mineral", dust.mineral);
      if (find_mineral(dust.mineral).symmetry() != CrystalSymmetry::Isotropic)
        d->fail("mineral", "a dust line's specks are isotropic (fluid, glass, an opaque or cubic mineral)");
      dust.size_mm = d->require<double>("size_mm", Range::open_closed(0, 0.1));
      dust.spacing_mm = d->require<double>("spacing_mm", Range::closed(dust.size_mm, 1.0));
      dust.fraction = d->get_or("fraction", 1.0, Range::closed(0, 1));
      og.dust = dust;
    }
    p.overgrowth = og;
  }
  if (const auto m = pr.optional_object("myrmekite")) p.myrmekite = read_myrmekite(*m);
  return p;
}

}  // namespace

// Krumbein's φ density is Gaussian; per millimetre it carries dφ/dL = −1/(L·ln 2).
double CsdRecipe::density(double size_mm) const {
  if (law == Law::log_linear) return std::exp(slope_per_mm * (size_mm - min_mm));
  const double z = (-std::log2(size_mm) + std::log2(median_mm)) / sorting_phi;
  return std::exp(-0.5 * z * z) / size_mm;
}

RockRecipe read_rock_recipe(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "rock recipe");
  if (!j.is_object()) throw InputError(path, "", "", "a rock recipe must hold a JSON object");
  const JsonReader r(j, path);
  RockRecipe rr;
  rr.path = path;
  rr.name = r.get_or<std::string>("name", std::filesystem::path(path).stem().string());
  rr.source = r.require<std::string>("source");
  rr.texture = r.get_or<std::string>("texture", "");
  rr.seed = static_cast<std::uint64_t>(r.get_or("seed", 1, Range::at_least(0)));
  rr.thickness_um = r.get_or("thickness_um", 30.0, Range::above(0));
  if (r.has("size_mm")) {
    const auto& s = j["size_mm"];
    if (!s.is_array() || s.size() != 2 || !s[0].is_number() || !s[1].is_number() || !(s[0].get<double>() > 0) ||
        !(s[1].get<double>() > 0) || s[0].get<double>() > 50 || s[1].get<double>() > 50)
      r.fail("size_mm", "expected [width, height] in mm, each in (0, 50]");
    rr.width_mm = s[0].get<double>();
    rr.height_mm = s[1].get<double>();
  }
  if (const auto m = r.optional_object("matrix")) {
    rr.matrix_mineral = m->require<std::string>("mineral");
    known_mineral(*m, "mineral", rr.matrix_mineral);
  }
  if (const auto g = r.optional_object("granoblastic")) {
    if (!rr.matrix_mineral.empty()) r.fail("granoblastic", "a granoblastic rock is holocrystalline: it has no matrix");
    GranoblasticRecipe gr;
    gr.grain_mm = g->require<double>("grain_mm", Range::closed(0.01, 10));
    gr.relax_iterations = g->get_or("relax_iterations", 12, Range::closed(0, 100));
    rr.granoblastic = gr;
  }
  double total = 0.0;
  for (const JsonReader& pr : r.objects("phases", 1)) {
    rr.phases.push_back(read_phase(pr, rr.granoblastic.has_value()));
    total += rr.phases.back().mode_percent;
    // Cement fills pores: it needs them, and its volume counts with the grains'.
    if (const auto& o = rr.phases.back().overgrowth) {
      if (rr.matrix_mineral.empty()) pr.fail("overgrowth", "cement fills pores, and this rock has no matrix (pore space)");
      total += o->cement_percent;
    }
  }
  // A myrmekite's bulbs grow into another phase of the rock (its mineral without composition).
  for (std::size_t k = 0; k < rr.phases.size(); ++k)
    if (const auto& m = rr.phases[k].myrmekite) {
      const bool hosted = std::any_of(rr.phases.begin(), rr.phases.end(), [&](const PhaseRecipe& q) {
        return &q != &rr.phases[k] && series_name(q.mineral) == series_name(m->host);
      });
      if (!hosted)
        throw InputError(rr.path, "phases[" + std::to_string(k) + "].myrmekite.host", m->host,
                         "no other phase of this rock is of that mineral: the bulbs would have nothing to grow into");
    }
  if (total > 100.0 + 1e-9) r.fail("phases", "the modes (and cements) sum to " + std::to_string(total) + " %, over 100");
  if (rr.matrix_mineral.empty() && std::abs(total - 100.0) > 1e-6)
    r.fail("phases", "without a matrix the modes must sum to 100 % (they sum to " + std::to_string(total) + ")");
  return rr;
}

std::string rock_recipe_path(const std::string& name) {
  namespace fs = std::filesystem;
  if (name.empty()) return "";
  std::error_code ec;
  // A bare name looks in assets/rocks (a path joined to it would replace the folder).
  if (fs::path(name).filename() == fs::path(name)) {
    const fs::path dir = fs::path(asset_dir()) / "rocks";
    for (const fs::path& p : {dir / name, dir / (name + ".json")})
      if (fs::is_regular_file(p, ec)) return p.string();
  }
  if (fs::is_regular_file(name, ec) && fs::path(name).extension() == ".json") {
    try {
      const nlohmann::json j = read_json_file(name, "rock recipe");
      if (j.is_object() && j.value("type", "") == "rock") return name;
    } catch (const InputError&) {
    }
  }
  return "";
}

}  // namespace pmsim
