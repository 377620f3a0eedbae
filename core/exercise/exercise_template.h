#pragma once
// An exercise template (assets/exercises/*.json, format in docs/exercises.md): the specimen every
// student gets a copy of, the rule that makes each copy different (a seed), and the tasks, each of
// a kind (exercise_kind.h) about one grain or the figure.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/exercise/exercise_kind.h"

namespace pmsim {

// How a student's seed makes their specimen:
//   section     — the template's thin section with every grain reoriented (sample.orientation_seed);
//   crystal     — a plate of a mineral drawn from `minerals`, its optic axis or acute bisectrix
//                 tilted up to `max_tilt_deg` from the microscope axis (conoscopic figures);
//   grain_mount — fragments of a mineral drawn from `minerals` in a liquid of n_D drawn from
//                 `medium_index` (the Becke-line test).
enum class SpecimenRule { Section, Crystal, GrainMount };

// A grain a template's tasks share: the largest grain of `mineral` for which every task on it
// has a truth (an extinction angle needs a cleavage trace or an elongation, a twin law a twin),
// chosen among the eligible by the seed. An empty mineral: any mineral. With `at_mm` the grain is
// the one under the crosshair at that stage position (stage.x_mm, stage.y_mm) in every student's
// section (the place is the same; its orientation is the student's).
struct GrainPick {
  std::string id;
  std::string mineral;
  std::optional<std::array<double, 2>> at_mm;
};

struct ExerciseTask {
  std::string id;                    // "q1": the key and the answers name tasks by it
  TaskKind kind = TaskKind::Identify;
  std::optional<double> tolerance;   // numeric kinds; unset: the kind's default
  std::string grain;                 // a GrainPick id; empty for the figure (crystal rule)
  std::string question;              // shown to the student; empty: the kind's question
};

struct ExerciseTemplate {
  std::string file;  // where it was read from (messages)
  std::string name;  // the file's stem, "granite-minerals"
  std::string title;
  std::string description;
  bool check_allowed = true;  // the app's Check button grades at once
  nlohmann::json scene;       // a scene object (the scene-file format) the specimen starts from
  SpecimenRule rule = SpecimenRule::Section;
  std::vector<std::string> minerals;         // crystal, grain_mount
  double max_tilt_deg = 8.0;                 // crystal
  std::array<double, 2> medium_index{1.50, 1.70};  // grain_mount: n_D range of the liquid
  std::vector<GrainPick> grains;
  std::vector<ExerciseTask> tasks;
};

// Parses a template; InputError naming the file, key and value on any fault (an unknown kind, a
// task naming no grain, a mineral not in the library, a scene key that is wrong).
ExerciseTemplate exercise_template_from_json(const nlohmann::json& j, const std::string& file);
// A template by path, or by name in <assets>/exercises ("granite-minerals").
ExerciseTemplate load_exercise_template(const std::string& name_or_path);
// The names of the shipped templates, sorted.
std::vector<std::string> exercise_template_names();

}  // namespace pmsim
