#include "core/exercise/student_exercise.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/base/input_error.h"
#include "core/base/splitmix64.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_series.h"
#include "core/exercise/colour_words.h"
#include "core/exercise/exercise_kind.h"
#include "core/exercise/mineral_signature.h"
#include "core/io/scene_file.h"
#include "core/microscope/figure_info.h"
#include "core/microscope/grain_report.h"
#include "core/microscope/map_section.h"
#include "core/microscope/section_map.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/grain_mount_truth.h"
#include "core/specimen/probe_point.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

namespace {

constexpr double kIndexNm = kGrainReportIndexWavelengthNm;  // n_D, the tables' wavelength

std::string fixed(double v, int digits) {
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}
double rounded(double v, int digits) {
  const double s = std::pow(10.0, digits);
  return std::round(v * s) / s;
}
// A draw in [0, 1) that depends on (seed, what, i) only.
double draw(std::uint32_t seed, std::uint64_t what, std::uint64_t i = 0) {
  return unit_interval(splitmix64(splitmix64(seed) ^ splitmix64(what * 0x9E3779B97F4A7C15ull + i)));
}
std::uint64_t text_hash(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}
double line_distance_deg(double a, double b) {  // between two lines, [0, 90]
  double d = std::fmod(std::abs(a - b), 180.0);
  return d > 90.0 ? 180.0 - d : d;
}
std::string angles_text(const std::vector<double>& a) {
  std::string s;
  for (std::size_t i = 0; i < a.size(); ++i) s += (i ? (i + 1 == a.size() ? " and " : ", ") : "") + fixed(a[i], 1) + "°";
  return s;
}

// The truths that do not depend on the grain's orientation.
std::optional<TaskTruth> mineral_truth(TaskKind kind, const std::string& mineral, double thickness_um) {
  const MineralSignature& f = cached_mineral_signature(mineral);
  // An opaque grain (magnetite, ilmenite) is black in plane and crossed light: naming it is the
  // only task it can answer; its character, 2V, birefringence or colours cannot be seen.
  if (f.opaque && kind != TaskKind::Identify) return std::nullopt;
  TaskTruth t;
  const std::string nd = " (indices at " + fixed(kIndexNm, 1) + " nm)";
  switch (kind) {
    case TaskKind::Identify:
      t.answer = series_name(mineral);
      t.explanation = "the grain is " + mineral;
      return t;
    case TaskKind::OpticCharacter:
      t.answer = f.character;
      t.explanation = mineral + " is " + f.character;
      return t;
    case TaskKind::OpticSign:
      if (f.optic_sign.empty()) return std::nullopt;
      t.answer = f.optic_sign;
      t.explanation = mineral + " is " + f.character + " " + f.optic_sign + nd;
      return t;
    case TaskKind::TwoV:
      if (f.character == "isotropic") return std::nullopt;
      if (f.character == "uniaxial") {
        t.answer = 0.0;
        t.explanation = mineral + " is uniaxial: the two optic axes coincide, 2V = 0°";
        return t;
      }
      t.answer = rounded(f.two_v_deg, 1);
      t.explanation = "2V = " + fixed(f.two_v_deg, 1) + "° about the acute bisectrix, from n_alpha, n_beta, n_gamma" + nd;
      return t;
    case TaskKind::Birefringence:
      if (f.character == "isotropic") return std::nullopt;
      t.answer = rounded(f.birefringence, 4);
      t.explanation = "n_gamma - n_alpha = " + fixed(f.n_max, 4) + " - " + fixed(f.n_min, 4) + " = " +
                      fixed(f.birefringence, 4) + nd;
      return t;
    case TaskKind::Pleochroism: {
      if (!f.pleochroic) return std::nullopt;
      const auto lab = principal_colours_lab(mineral, thickness_um);
      t.answer = pleochroism_words(mineral, thickness_um);
      std::string measured;
      for (int a = 0; a < 3; ++a)
        measured += std::string(a ? "; " : "") + "XYZ"[a] + " L* " + fixed(lab[std::size_t(a)].x, 0) + " a* " +
                    fixed(lab[std::size_t(a)].y, 0) + " b* " + fixed(lab[std::size_t(a)].z, 0);
      t.explanation = "white light through " + fixed(thickness_um, 0) + " µm vibrating along X, Y, Z: " +
                      t.answer.get<std::string>() + " (" + measured + "; the nearest words of the colour table)";
      return t;
    }
    case TaskKind::MaxInterferenceOrder: {
      if (f.character == "isotropic") return std::nullopt;
      const double gamma_nm = 1000.0 * thickness_um * f.birefringence;
      const int order = std::max(1, int(std::ceil(gamma_nm / kOrderWavelengthNm)));
      t.answer = order;
      t.explanation = "a grain cut with n_gamma and n_alpha in its plane shows " + fixed(thickness_um, 0) + " µm × " +
                      fixed(f.birefringence, 4) + " = " + fixed(gamma_nm, 0) + " nm: order " +
                      std::to_string(order) + " (orders end at multiples of 550 nm)";
      return t;
    }
    default:
      return std::nullopt;
  }
}

std::optional<TaskTruth> extinction_truth(TaskKind kind, const GrainReport& r) {
  // The report's angle is measured from the first cleavage trace, else the elongation.
  if (r.extinction_stage_deg.empty() || !r.slow_vibration_deg || !r.extinction_angle_deg) return std::nullopt;
  const bool cleavage = !r.cleavage_traces_deg.empty();
  const double ref = cleavage ? r.cleavage_traces_deg.front() : *r.elongation_deg;
  const double angle = *r.extinction_angle_deg;
  const std::string seen = "extinct at stage " + angles_text(r.extinction_stage_deg) + "; the " +
                           (cleavage ? "cleavage trace" : "elongation") + " lies at " + fixed(ref, 1) +
                           "° at stage 0° (counter-clockwise from E-W)";
  TaskTruth t;
  t.extinction_stage_deg = r.extinction_stage_deg;
  if (kind == TaskKind::ExtinctionAngle) {
    t.answer = rounded(angle, 1);
    t.explanation = seen + ", so the extinction angle is " + fixed(angle, 1) + "°";
    return t;
  }
  // Symmetric: a vibration direction bisects two cleavage traces (amphibole, calcite).
  bool symmetric = false;
  if (r.cleavage_traces_deg.size() >= 2) {
    const double a = r.cleavage_traces_deg[0];
    double d = std::fmod(r.cleavage_traces_deg[1] - a, 180.0);  // b − a as lines, in (−90°, 90°]
    if (d > 90.0) d -= 180.0;
    if (d <= -90.0) d += 180.0;
    // Either vibration direction on either bisector: folding modulo 90° covers all four.
    if (std::abs(d) > 10.0)
      symmetric = is_parallel_extinction(folded_extinction_angle_deg(line_distance_deg(*r.slow_vibration_deg, a + 0.5 * d)));
  }
  const std::string type = symmetric ? "symmetric" : is_parallel_extinction(angle) ? "parallel" : "inclined";
  t.answer = type;
  t.explanation = seen + (symmetric ? ", and the vibration directions bisect the two cleavage traces"
                                    : ", the extinction angle is " + fixed(angle, 1) + "°") +
                  ": " + type + " extinction";
  return t;
}

std::optional<TaskTruth> grain_truth(TaskKind kind, const Scene& scene, const SectionGrain& g, const GrainReport& r) {
  TaskTruth t;
  switch (kind) {
    case TaskKind::ExtinctionAngle:
    case TaskKind::ExtinctionType:
      return extinction_truth(kind, r);
    case TaskKind::SignOfElongation:
      if (!r.sign_of_elongation || *r.sign_of_elongation == SignOfElongation::Indeterminate || !r.elongation_deg ||
          !r.slow_vibration_deg)
        return std::nullopt;
      t.answer = sign_of_elongation_name(*r.sign_of_elongation);
      t.explanation = "the elongation lies at " + fixed(*r.elongation_deg, 1) + "°, the slow vibration at " +
                      fixed(*r.slow_vibration_deg, 1) + "° (stage 0°): " + t.answer.get<std::string>();
      return t;
    case TaskKind::TwinLaw:
      if (!r.twin || r.twin->law.empty()) return std::nullopt;
      t.answer = r.twin->law;
      t.explanation = "the grain is twinned on the " + r.twin->law + " law; the twin individual is extinct at stage " +
                      angles_text(r.twin->extinction_stage_deg);
      return t;
    case TaskKind::ReliefVsMedium:
      return std::nullopt;  // a grain-mount task (the liquid is the medium)
    default:
      return mineral_truth(kind, g.mineral, scene.sample.thickness_um);
  }
}

struct GrainCandidate {
  int label;
  double size;
  std::vector<TaskTruth> truths;
};

// Grain k with the truth of every task on it, or nullopt when one has none.
std::optional<GrainCandidate> grain_candidate(const SectionMap& section, const Scene& scene, int k,
                                              const std::vector<const ExerciseTask*>& tasks) {
  const SectionGrain& g = section.grains[std::size_t(k - 1)];
  const GrainReport r = report_grain(scene, section, k);
  GrainCandidate c{k, g.semi_major_mm + g.semi_minor_mm, {}};
  for (const ExerciseTask* task : tasks) {
    auto truth = grain_truth(task->kind, scene, g, r);
    if (!truth) return std::nullopt;
    c.truths.push_back(std::move(*truth));
  }
  return c;
}

// The grain of a pick: under its stage position, or drawn by the seed among the larger half of
// the eligible grains of its mineral (students get different grains).
GrainCandidate pick_grain(const ExerciseTemplate& tp, const GrainPick& pick, const SectionMap& section,
                          const StudentExercise& ex, const std::vector<const ExerciseTask*>& tasks,
                          const std::vector<int>& taken) {
  const auto refuse = [&](const std::string& why) {
    return InputError(tp.file, "grains", pick.id, why + " (seed " + std::to_string(ex.seed) + ")");
  };
  if (pick.at_mm) {
    const int k = section.grain_label(section.domain_at({(*pick.at_mm)[0], (*pick.at_mm)[1]}));
    if (k == 0) throw refuse("no grain under the crosshair at its at_mm");
    const std::string m = series_name(canonical_mineral_name(section.grains[std::size_t(k - 1)].mineral));
    if (!pick.mineral.empty() && m != pick.mineral) throw refuse("the grain at its at_mm is " + m + ", not " + pick.mineral);
    auto c = grain_candidate(section, ex.scene, k, tasks);
    if (!c) throw refuse("the " + m + " at its at_mm has no truth for every task on it in this orientation");
    return std::move(*c);
  }
  std::vector<GrainCandidate> eligible;
  for (int k = 1; k <= int(section.grains.size()); ++k) {
    const SectionGrain& g = section.grains[std::size_t(k - 1)];
    if (!pick.mineral.empty() && series_name(canonical_mineral_name(g.mineral)) != pick.mineral) continue;
    if (std::find(taken.begin(), taken.end(), k) != taken.end()) continue;
    // The grain's centre must lie in the grain (not in a crack or a neighbour's cell).
    if (section.grain_label(section.domain_at(g.centre_mm)) != k) continue;
    if (auto c = grain_candidate(section, ex.scene, k, tasks)) eligible.push_back(std::move(*c));
  }
  if (eligible.empty())
    throw refuse("no grain" + (pick.mineral.empty() ? std::string() : " of " + pick.mineral) +
                 " in this student's section has a truth for every task on it");
  std::stable_sort(eligible.begin(), eligible.end(), [](const auto& a, const auto& b) { return a.size > b.size; });
  const double cut = 0.5 * eligible.front().size;
  std::size_t n = 0;
  while (n < eligible.size() && eligible[n].size >= cut) ++n;
  return std::move(eligible[std::size_t(draw(ex.seed, text_hash(pick.id)) * double(n))]);
}

void section_exercise(const ExerciseTemplate& tp, StudentExercise& ex) {
  ex.scene.sample.orientation_seed = int(ex.seed);
  const std::shared_ptr<const SectionMap> section = load_scene_section(ex.scene);
  std::vector<int> taken;
  for (const GrainPick& pick : tp.grains) {
    std::vector<const ExerciseTask*> tasks;
    for (const auto& task : tp.tasks)
      if (task.grain == pick.id) tasks.push_back(&task);
    GrainCandidate c = pick_grain(tp, pick, *section, ex, tasks, taken);
    taken.push_back(c.label);
    const SectionGrain& g = section->grains[std::size_t(c.label - 1)];
    const std::array<double, 2> at = pick.at_mm ? *pick.at_mm : std::array<double, 2>{g.centre_mm.x, g.centre_mm.y};
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      StudentTask st{*tasks[i], at, c.label, "", std::move(c.truths[i])};
      st.where = "grain " + pick.id + ": the grain under the crosshair with the stage at x = " + fixed(at[0], 3) +
                 " mm, y = " + fixed(at[1], 3) + " mm";
      ex.tasks.push_back(std::move(st));
    }
  }
}

// The minerals of a template for which every task has a truth.
std::vector<std::string> eligible_minerals(const ExerciseTemplate& tp, double thickness_um, bool mount) {
  std::vector<std::string> out;
  for (const std::string& m : tp.minerals) {
    bool ok = true;
    for (const auto& task : tp.tasks)
      if (!(mount && task.kind == TaskKind::ReliefVsMedium) && !mineral_truth(task.kind, m, thickness_um)) ok = false;
    if (ok) out.push_back(m);
  }
  if (out.empty())
    throw InputError(tp.file, "specimen.minerals", "", "no mineral of the list has a truth for every task");
  return out;
}

// A plate whose optic axis (uniaxial) or acute bisectrix (biaxial) is tilted up to max_tilt_deg
// from the microscope axis in a random azimuth, the optic-axial plane at a random azimuth: the
// centred or slightly off-centre figure a student is given to read.
void crystal_exercise(const ExerciseTemplate& tp, StudentExercise& ex) {
  Scene& s = ex.scene;
  const auto minerals = eligible_minerals(tp, s.sample.thickness_um, false);
  const std::string mineral = minerals[std::size_t(draw(ex.seed, 1) * double(minerals.size()))];
  s.sample.type = SampleType::Plate;
  s.sample.mineral = mineral;
  s.sample.crystal.reset();
  s.sample.cut.reset();
  // sqrt: uniform over the cap's area for small tilts.
  const double tilt = tp.max_tilt_deg * std::sqrt(draw(ex.seed, 2)) * std::numbers::pi / 180.0;
  const double az = 2.0 * std::numbers::pi * draw(ex.seed, 3), psi = 2.0 * std::numbers::pi * draw(ex.seed, 4);
  const glm::dvec3 b{std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)};
  const glm::dvec3 h{std::cos(psi), std::sin(psi), 0.0};
  const glm::dvec3 o = glm::normalize(h - glm::dot(h, b) * b);
  const MineralSignature& f = cached_mineral_signature(mineral);
  const auto arr = [](const glm::dvec3& v) { return std::array<double, 3>{v.x, v.y, v.z}; };
  if (f.character == "uniaxial") s.sample.optic_axis = arr(b);
  if (f.character == "biaxial") {
    s.sample.z_axis = arr(f.optic_sign == "positive" ? b : o);
    s.sample.x_axis = arr(f.optic_sign == "positive" ? o : b);
  }
  const FigureInfo fig = describe_figure(s);
  for (const auto& task : tp.tasks) {
    TaskTruth t = *mineral_truth(task.kind, mineral, s.sample.thickness_um);
    if (task.kind == TaskKind::OpticCharacter || task.kind == TaskKind::OpticSign || task.kind == TaskKind::TwoV)
      t.explanation = fig.orientation + " (" + fixed(fig.axis_tilt_deg, 1) + "° off the axis); " +
                      (fig.compensator.empty() ? std::string() : fig.compensator + "; ") + t.explanation;
    ex.tasks.push_back(StudentTask{task, std::nullopt, 0, "the figure in the field centre", std::move(t)});
  }
}

// The largest fragment of the field: its label and the stage position of its pixels' centroid.
std::pair<int, std::array<double, 2>> largest_fragment(const SpecimenScene& mount, const Scene& probe) {
  const auto labels = fragment_label_image(mount, probe);
  const int w = probe.render.width, h = probe.render.height;
  std::vector<double> n(mount.fragment_count() + 1, 0.0), sx(n.size(), 0.0), sy(n.size(), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint16_t l = labels[std::size_t(y) * std::size_t(w) + std::size_t(x)];
      n[l] += 1.0, sx[l] += x + 0.5, sy[l] += y + 0.5;
    }
  std::size_t best = 0;
  for (std::size_t l = 1; l < n.size(); ++l)
    if (n[l] > n[best] || best == 0) best = n[l] > 0 ? l : best;
  if (best == 0 || n[best] == 0.0) throw InputError("", "sample", "grains", "the mount shows no fragment in the field");
  const ProbePoint p = probe_point(probe, sx[best] / n[best] / w, sy[best] / n[best] / h);
  return {int(best), {p.specimen_um.x / 1000.0, p.specimen_um.y / 1000.0}};
}

// Fragments of a mineral drawn from the list in a liquid drawn from the range, the liquid at
// least 0.01 from the fragment's n' so that the Becke line is plain (matched liquids are their
// own lesson).
void grain_mount_exercise(const ExerciseTemplate& tp, StudentExercise& ex) {
  Scene& s = ex.scene;
  const auto minerals = eligible_minerals(tp, s.sample.thickness_um, true);
  s.sample.type = SampleType::Grains;
  s.sample.mineral = minerals[std::size_t(draw(ex.seed, 1) * double(minerals.size()))];
  s.sample.crystal.reset();
  s.sample.medium_index = tp.medium_index[0];
  Scene probe = s;
  probe.render.width = probe.render.height = 96;
  probe.stage = {};
  // Not a structured binding: clang 14 (the sanitizer build) cannot capture one in a lambda.
  const std::pair<int, std::array<double, 2>> largest = largest_fragment(*grain_mount_specimen_cached(probe), probe);
  const int label = largest.first;
  const std::array<double, 2> stage_mm = largest.second;
  s.stage.x_mm = stage_mm[0], s.stage.y_mm = stage_mm[1];
  probe.stage = s.stage;
  // n′ of the fragment does not depend on the liquid: read it once, draw the liquid against it,
  // then take the truth from the mount in that liquid (one more build, not one per draw).
  const auto n_of = [&](const Scene& sc) -> std::optional<FragmentTruth> {
    const auto mount = grain_mount_specimen_cached(sc);
    for (const FragmentTruth& f : fragment_truths(*mount, sc, fragment_label_image(*mount, sc)))
      if (f.label == label) return f;
    return std::nullopt;
  };
  const std::optional<FragmentTruth> first = n_of(probe);
  if (!first) throw InputError(tp.file, "specimen", "", "the fragment under the crosshair is not in the field");
  bool drawn = false;
  for (int attempt = 0; attempt < 64 && !drawn; ++attempt) {
    const double lo = tp.medium_index[0], hi = tp.medium_index[1];
    probe.sample.medium_index = std::round((lo + (hi - lo) * draw(ex.seed, 5, std::uint64_t(attempt))) * 500.0) / 500.0;
    drawn = std::abs(first->n_polarizer - *probe.sample.medium_index) > 0.01;
  }
  if (!drawn) throw InputError(tp.file, "specimen.medium_index", "", "no liquid in the range is 0.01 from the fragment's index");
  const std::optional<FragmentTruth> truth = n_of(probe);
  s.sample.medium_index = probe.sample.medium_index;
  const std::string where = "the fragment under the crosshair with the stage at x = " + fixed(stage_mm[0], 3) +
                            " mm, y = " + fixed(stage_mm[1], 3) + " mm";
  for (const auto& task : tp.tasks) {
    TaskTruth t;
    if (task.kind == TaskKind::ReliefVsMedium) {
      t.answer = truth->relief_vs_medium;
      t.explanation = "n' along the polarizer = " + fixed(truth->n_polarizer, 4) + " at stage 0°, the liquid's n_D = " +
                      fixed(truth->liquid_n_d, 3) + ": relief " + truth->relief_vs_medium +
                      " (the Becke line moves toward the higher index on raising the focus)";
    } else {
      t = *mineral_truth(task.kind, s.sample.mineral, s.sample.thickness_um);
    }
    ex.tasks.push_back(StudentTask{task, stage_mm, label, where, std::move(t)});
  }
}

}  // namespace

StudentExercise make_student_exercise(const ExerciseTemplate& t, const std::string& student, std::uint32_t seed) {
  StudentExercise ex;
  ex.student = student;
  ex.seed = seed & 0x7fffffffu;
  ex.scene = scene_from_json(t.scene, t.file + " (specimen.scene)");
  ex.scene.stage_deg = 0.0;
  switch (t.rule) {
    case SpecimenRule::Section: section_exercise(t, ex); break;
    case SpecimenRule::Crystal: crystal_exercise(t, ex); break;
    case SpecimenRule::GrainMount: grain_mount_exercise(t, ex); break;
  }
  // Keep the template's task order (grains group them while picking).
  std::vector<StudentTask> ordered;
  for (const auto& spec : t.tasks)
    for (auto& task : ex.tasks)
      if (task.spec.id == spec.id) ordered.push_back(std::move(task));
  ex.tasks = std::move(ordered);
  for (const auto& task : ex.tasks)
    if (task.stage_mm) {
      ex.scene.stage.x_mm = (*task.stage_mm)[0];
      ex.scene.stage.y_mm = (*task.stage_mm)[1];
      break;
    }
  validate_scene(ex.scene, t.file + " (student " + student + ")");
  return ex;
}

}  // namespace pmsim
