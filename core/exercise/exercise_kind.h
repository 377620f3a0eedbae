#pragma once
// The kinds of task an exercise asks (issue 23): what the answer is (a number with a unit, or a
// choice from a list) and how an answer is compared with the truth. One table, read by the
// template reader, the key maker, the grader and the app's Exercise panel.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace pmsim {

// Up to this an extinction is called parallel: micas and other "parallel" minerals extinguish
// within 0-3° of their cleavage (Nesse 2012 ch. 14), and a student's setting of the darkest
// position scatters by 1-2°; the default tolerance of an extinction angle is the same. One rule
// for the key's truths and the identification's signatures.
inline constexpr double kParallelExtinctionDeg = 3.0;
// Whether an extinction angle, folded into [0°, 45°], counts as parallel.
inline bool is_parallel_extinction(double folded_angle_deg) { return folded_angle_deg <= kParallelExtinctionDeg; }

enum class TaskKind {
  Identify,              // the mineral (library names and aliases)
  ExtinctionAngle,       // deg, to the cleavage trace or elongation, folded into [0°, 45°]
  ExtinctionType,        // parallel | inclined | symmetric
  SignOfElongation,      // length-slow | length-fast
  OpticCharacter,        // uniaxial | biaxial | isotropic
  OpticSign,             // positive | negative
  TwoV,                  // deg, about the acute bisectrix [0°, 90°]
  MaxInterferenceOrder,  // the highest order a mineral shows at the section's thickness (1, 2, …)
  Birefringence,         // n_γ − n_α (uniaxial |n_ε − n_ω|) at 589.3 nm
  ReliefVsMedium,        // higher | lower | matched (the Becke line)
  TwinLaw,               // a twin law of the mineral file ("albite", "carlsbad", …)
  Pleochroism,           // "X, Y, Z" colour words of assets/exercises/pleochroic_colours.json
};

struct TaskKindInfo {
  TaskKind kind;
  const char* name;               // as written in templates and key files
  bool numeric;                   // a number (within a tolerance) or a word from a list
  double default_tolerance;       // numeric kinds, in `unit`
  const char* unit;               // "deg", "" …
  std::vector<std::string> choices;  // word kinds with a closed list (empty: identify, twin_law)
  const char* question;           // what the student is asked
};

const std::vector<TaskKindInfo>& task_kinds();
const TaskKindInfo& task_kind_info(TaskKind kind);
std::optional<TaskKind> find_task_kind(std::string_view name);  // case-insensitive
std::string task_kind_list();                                    // "identify|extinction_angle|…"

// An answer in the one spelling the grader compares: numbers as numbers; words lower case,
// trimmed, with the kind's synonyms ("+" → "positive", "length slow" → "length-slow"), a mineral
// name through the library's aliases to its series name ("cpx" → "augite", "plagioclase:An30" →
// "plagioclase"). nullopt for an answer that is not of the kind's type (a word for a number).
std::optional<nlohmann::json> normalized_answer(TaskKind kind, const nlohmann::json& answer);

// Whether `answer` is right: numbers within `tolerance` (extinction angles folded into
// [0°, 45°] first, since the two vibration directions are 90° apart and the angle is unsigned);
// words equal after normalized_answer; pleochroism three colour words (X, Y, Z; separated by
// commas or slashes), each the expected word or the word nearest to it in the table (colour_words.h:
// neighbouring words of a descriptive scale are what two observers differ by). A null or malformed
// answer is wrong.
bool answer_correct(TaskKind kind, const nlohmann::json& answer, const nlohmann::json& expected,
                    std::optional<double> tolerance);

// An extinction angle folded into [0°, 45°]: the angle between a line and the nearer of two
// perpendicular lines.
double folded_extinction_angle_deg(double deg);

}  // namespace pmsim
