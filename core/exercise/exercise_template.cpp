#include "core/exercise/exercise_template.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "core/base/asset_locator.h"
#include "core/base/json_reader.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_series.h"
#include "core/io/scene_file.h"

namespace pmsim {

namespace {

const NameTable<SpecimenRule> kRules{
    {"section", SpecimenRule::Section}, {"crystal", SpecimenRule::Crystal}, {"grain_mount", SpecimenRule::GrainMount}};

std::vector<std::string> read_minerals(const JsonReader& spec) {
  std::vector<std::string> out;
  const nlohmann::json* list = spec.find("minerals");
  if (!list) return out;
  if (!list->is_array() || list->empty()) spec.fail("minerals", *list, "expected a non-empty list of mineral names");
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string key = "minerals[" + std::to_string(i) + "]";
    const std::string name = spec.checked(key, (*list)[i], [](const nlohmann::json& v) { return string_value(v); });
    try {
      out.push_back(canonical_mineral_name(name));
    } catch (const InputError& e) {
      spec.fail(key, (*list)[i], e.reason);
    }
  }
  return out;
}

void read_specimen(const JsonReader& root, ExerciseTemplate& t) {
  const JsonReader spec = root.object("specimen");
  spec.refuse_unknown_keys({"rule", "scene", "minerals", "max_tilt_deg", "medium_index"});
  t.rule = spec.require_enum("rule", kRules);
  t.scene = spec.object("scene").node();
  // The scene must be one the renderer takes, before any student gets it.
  scene_from_json(t.scene, t.file + " (specimen.scene)");
  t.minerals = read_minerals(spec);
  if (t.rule != SpecimenRule::Section && t.minerals.empty())
    spec.fail("minerals", "a crystal or grain_mount rule needs a list of minerals to draw from");
  t.max_tilt_deg = spec.get_or("max_tilt_deg", 8.0, Range::closed(0.0, 30.0));
  if (const nlohmann::json* m = spec.find("medium_index")) {
    const auto r = spec.checked("medium_index", *m, [](const nlohmann::json& v) {
      if (!v.is_array() || v.size() != 2) throw BadValue{"expected [low, high]"};
      return std::array<double, 2>{number_value(v[0]), number_value(v[1])};
    });
    if (!(r[0] >= 1.40 && r[1] <= 1.80 && r[0] < r[1]))
      spec.fail("medium_index", *m, "expected 1.40 ≤ low < high ≤ 1.80 (the immersion-liquid series)");
    t.medium_index = r;
  }
}

void read_tasks(const JsonReader& root, ExerciseTemplate& t) {
  for (const JsonReader& g : root.has("grains") ? root.objects("grains") : std::vector<JsonReader>{}) {
    g.refuse_unknown_keys({"id", "mineral", "at_mm"});
    GrainPick p{g.require<std::string>("id"), g.get_or<std::string>("mineral", ""), std::nullopt};
    if (const nlohmann::json* at = g.find("at_mm"))
      p.at_mm = g.checked("at_mm", *at, [](const nlohmann::json& v) {
        if (!v.is_array() || v.size() != 2) throw BadValue{"expected a stage position [x_mm, y_mm]"};
        const std::array<double, 2> xy{number_value(v[0]), number_value(v[1])};
        if (!(std::abs(xy[0]) <= 1000 && std::abs(xy[1]) <= 1000)) throw BadValue{"expected |x|, |y| ≤ 1000 mm"};
        return xy;
      });
    if (!p.mineral.empty()) {
      try {
        p.mineral = series_name(canonical_mineral_name(p.mineral));
      } catch (const InputError& e) {
        g.fail("mineral", e.reason);
      }
    }
    t.grains.push_back(std::move(p));
  }
  std::set<std::string> ids;
  for (const JsonReader& r : root.objects("tasks", 1)) {
    r.refuse_unknown_keys({"task", "kind", "tolerance", "grain", "question"});
    ExerciseTask task;
    task.id = r.require<std::string>("task");
    if (task.id.empty() || !ids.insert(task.id).second) r.fail("task", "task ids must be non-empty and unique");
    const std::string kind = r.require<std::string>("kind");
    const auto k = find_task_kind(kind);
    if (!k) r.fail("kind", "expected one of " + task_kind_list());
    task.kind = *k;
    task.tolerance = r.optional<double>("tolerance", Range::at_least(0.0));
    if (task.tolerance && !task_kind_info(task.kind).numeric)
      r.fail("tolerance", "a " + kind + " answer is a word: it has no tolerance");
    task.grain = r.get_or<std::string>("grain", "");
    task.question = r.get_or<std::string>("question", "");
    const bool figure_rule = t.rule == SpecimenRule::Crystal;
    if (!figure_rule && task.grain.empty()) r.fail("grain", "a task on a section or mount names the grain it is about");
    if (!figure_rule &&
        std::none_of(t.grains.begin(), t.grains.end(), [&](const GrainPick& g) { return g.id == task.grain; }))
      r.fail("grain", "no grain with this id in 'grains'");
    if (figure_rule && !task.grain.empty()) r.fail("grain", "a crystal template's tasks are about its figure");
    t.tasks.push_back(std::move(task));
  }
}

}  // namespace

ExerciseTemplate exercise_template_from_json(const nlohmann::json& j, const std::string& file) {
  ExerciseTemplate t;
  t.file = file;
  t.name = std::filesystem::path(file).stem().string();
  const JsonReader root(j, file);
  root.refuse_unknown_keys({"type", "title", "description", "source", "check", "specimen", "grains", "tasks"});
  if (root.require<std::string>("type") != "exercise_template")
    root.fail("type", "an exercise template has \"type\": \"exercise_template\"");
  t.title = root.require<std::string>("title");
  t.description = root.get_or<std::string>("description", "");
  t.check_allowed = root.get_or("check", true);
  read_specimen(root, t);
  read_tasks(root, t);
  return t;
}

ExerciseTemplate load_exercise_template(const std::string& name_or_path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string path = name_or_path;
  if (!fs::is_regular_file(path, ec)) {
    const fs::path dir = fs::path(asset_dir()) / "exercises";
    for (const fs::path& p : {dir / name_or_path, dir / (name_or_path + ".json")})
      if (fs::is_regular_file(p, ec)) path = p.string();
  }
  if (!fs::is_regular_file(path, ec))
    throw InputError(name_or_path, "", "",
                     "no such exercise template (a file, or one of: " + [] {
                       std::string all;
                       for (const auto& n : exercise_template_names()) all += (all.empty() ? "" : ", ") + n;
                       return all;
                     }() + ")");
  return exercise_template_from_json(read_json_file(path, "exercise template"), path);
}

std::vector<std::string> exercise_template_names() {
  namespace fs = std::filesystem;
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(asset_dir()) / "exercises", ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace pmsim
