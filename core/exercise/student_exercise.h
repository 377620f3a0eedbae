#pragma once
// One student's exercise: the template's specimen made different by the student's seed, where
// each task's grain is, and the truth of every task with how it is measured. The truth is never
// written to the student's file: the key holds it, and the app recomputes it from the template
// and the seed when the template allows checking.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/exercise/exercise_template.h"
#include "core/microscope/scene.h"

namespace pmsim {

struct TaskTruth {
  nlohmann::json answer;             // a number or a word, in the kind's spelling
  std::string explanation;           // how it is measured, with this specimen's numbers
  // Stage angles in [0°, 180°) at which the grain is extinct between crossed polars (with the
  // polarizer at the scene's angle): extinction tasks, so that a rendered sweep can check them.
  std::vector<double> extinction_stage_deg;
};

struct StudentTask {
  ExerciseTask spec;
  // The stage position that puts the task's grain under the crosshair (mm, the scene's
  // stage.x_mm / stage.y_mm); unset for the figure of a crystal.
  std::optional<std::array<double, 2>> stage_mm;
  int grain_label = 0;  // section: the grain's label (--labels); grain mount: the fragment's
  std::string where;    // the grain, in words: "the biotite under the crosshair at x = …"
  TaskTruth truth;
};

struct StudentExercise {
  std::string student;
  std::uint32_t seed = 0;
  Scene scene;  // the specimen, crosshair on the first task's grain
  std::vector<StudentTask> tasks;
};

// Draws the student's specimen and answers from `seed` (0 … 2³¹ − 1). Throws InputError naming the
// template when it cannot be made, e.g. no grain of a mineral the template asks for has a truth
// for all its tasks.
StudentExercise make_student_exercise(const ExerciseTemplate& t, const std::string& student, std::uint32_t seed);

}  // namespace pmsim
