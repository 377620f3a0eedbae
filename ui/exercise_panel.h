#pragma once
// Private to the App: a class exercise open in the app (issue 23; docs/exercises.md "In the app").
// The student file names the template and the seed; its tasks are listed in the Exercise tab,
// where the student types the answers (numbers, or words from the kind's list). The answers are
// saved to <student>.answers.json (exercise_files.h answers_path_for), atomically. Check makes the
// exercise again from the template and the seed (the truth never is in the student's file) and
// grades the answers with core's grader; after that the reveal layer draws the ground truth of the
// field (core/exercise/reveal_geometry.h), recomputed whenever the scene (stage) changes.
#include <array>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/exercise/exercise_files.h"
#include "core/exercise/exercise_kind.h"
#include "core/exercise/reveal_geometry.h"
#include "core/exercise/student_exercise.h"

namespace pmsim::ui {

struct ExerciseTaskView {
  std::string id, grain, question, where, unit;  // grain: the template's grain id ("A"), or ""
  TaskKind kind = TaskKind::Identify;
  std::vector<std::string> choices;              // the kind's list (identify: the library's minerals)
  std::optional<std::array<double, 2>> stage_mm; // puts the task's grain under the crosshair
};

struct ExerciseSession {
  StudentFile file;  // path, student, template name, seed, scene
  std::string answers_path, title, description;
  bool check_allowed = true;
  std::vector<ExerciseTaskView> tasks;
  std::vector<std::string> answers;  // as typed, one per task
  bool unsaved = false;
  std::string saved_at;  // the last save's path ("" before the first)

  // Check: the exercise made again (kept: the truth does not change) and the graded answers.
  struct Checked {
    std::shared_ptr<const StudentExercise> truth;
    std::optional<GradedStudent> graded;
    std::string error;
  };
  std::shared_ptr<const StudentExercise> truth;
  std::optional<GradedStudent> graded;
  std::future<Checked> check_job;

  // The reveal layer: shown after a Check, recomputed for each new scene (the stage turns).
  bool reveal = false;
  std::optional<RevealGeometry> geometry;
  std::uint64_t geometry_generation = ~0ull;  // the scene `geometry` (or the job in flight) is of
  std::uint64_t job_generation = ~0ull;
  std::future<RevealGeometry> geometry_job;
  std::string geometry_error;

  int focus_task = -1;      // give this task's answer field the keyboard focus on the next frame
  bool select_tab = false;  // bring the Exercise tab to the front on the next frame
};

// Reads a student file into a session (InputError naming the file and key), and the answers
// saved beside it, if any (a malformed answers file is an InputError too).
ExerciseSession read_exercise_session(const std::string& path);
// An answer as the grader takes it: null when empty; numeric kinds a number when the text is one
// (else the text, which grades wrong, as a word for a number does); words as typed, trimmed.
nlohmann::json typed_answer(const ExerciseTaskView& task, const std::string& text);
StudentAnswers session_answers(const ExerciseSession& s);
// The task index of `id` (case-sensitive), or -1.
int exercise_task_index(const ExerciseSession& s, const std::string& id);

// Colours the tests read back (the summary badges, the reveal layer), sRGB 8-bit.
inline constexpr std::array<int, 3> kBadgeRight{40, 190, 80};
inline constexpr std::array<int, 3> kBadgeWrong{220, 50, 50};
inline constexpr std::array<int, 3> kRevealOutline{255, 235, 90};
inline constexpr std::array<int, 3> kRevealSlow{255, 80, 60};
inline constexpr std::array<int, 3> kRevealFast{250, 250, 250};
inline constexpr std::array<int, 3> kRevealCleavage{120, 200, 255};
inline constexpr std::array<int, 3> kRevealIndicatrix{200, 120, 255};
inline constexpr int kBadgeSize = 12;  // px, the summary row's squares

}  // namespace pmsim::ui
