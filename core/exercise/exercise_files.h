#pragma once
// The files of a class exercise (contracts of issue 23; docs/exercises.md):
//   <student>.pmexercise.json  what a student opens: template, seed, the specimen's scene and the
//                              tasks' questions and grain positions; no answer in it;
//   key.json                   {"students": [{"student", "exercise", "tasks": [{"task", "kind",
//                              "answer", "tolerance", "explanation"}]}]} (+ seed, template, where);
//   answers                    {"student": ID, "answers": [{"task": TASK_ID, "answer": VALUE}]};
//   the report                 CSV rows "student,task,kind,answer,expected,correct" and JSON with
//                              each student's score in [0, 1].
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/exercise/student_exercise.h"

namespace pmsim {

nlohmann::json student_file_json(const ExerciseTemplate& t, const StudentExercise& ex);

// A student file read back: its template (by name, from the assets) and seed make the exercise
// again, truth included (what the app's Check grades with). InputError naming the file and key.
struct StudentFile {
  std::string path, student, template_name;
  std::uint32_t seed = 0;
  nlohmann::json scene;  // the "scene" object
};
StudentFile read_student_file(const std::string& path);
bool is_student_file(const nlohmann::json& j);  // "type": "pmexercise"

nlohmann::json key_student_json(const StudentExercise& ex, const std::string& exercise_file);

struct KeyTask {
  std::string task;
  TaskKind kind = TaskKind::Identify;
  nlohmann::json answer;
  std::optional<double> tolerance;
  std::string explanation;
};
struct KeyStudent {
  std::string student, exercise;
  std::vector<KeyTask> tasks;
};
std::vector<KeyStudent> read_key_file(const std::string& path);
// The key entry of an exercise made in memory (what the app's Check grades against).
KeyStudent key_student(const StudentExercise& ex, const std::string& exercise_file = "");

struct StudentAnswers {
  std::string path, student;
  std::vector<std::pair<std::string, nlohmann::json>> answers;  // task id → answer (file order)
};
StudentAnswers read_answers_file(const std::string& path);
// Where a student's answers to `student_file` are saved: <folder>/<stem>.answers.json beside it,
// the stem being the file name less ".pmexercise.json".
std::string answers_path_for(const std::string& student_file);
nlohmann::json answers_json(const StudentAnswers& a);

struct GradedTask {
  std::string student, task;
  TaskKind kind = TaskKind::Identify;
  std::optional<nlohmann::json> answer;  // unset: not answered (wrong)
  nlohmann::json expected;
  std::optional<double> tolerance;
  bool correct = false;
  std::string explanation;
};
struct GradedStudent {
  std::string student;
  bool submitted = false;
  std::vector<GradedTask> tasks;
  double score() const;  // correct / tasks, in [0, 1]
};

// Grades one student's answers against their key entry (an answer to no task of theirs is ignored).
GradedStudent grade_student(const KeyStudent& key, const StudentAnswers* answers);
// Every student of the key, in key order; InputError when an answers file names a student not in
// the key or two files answer for the same student.
std::vector<GradedStudent> grade_class(const std::vector<KeyStudent>& key, const std::vector<StudentAnswers>& answers);

std::string report_csv(const std::vector<GradedStudent>& graded);
nlohmann::json report_json(const std::vector<GradedStudent>& graded);

// An answer as the CSV shows it: strings bare, numbers in shortest form, missing empty.
std::string answer_text(const std::optional<nlohmann::json>& v);

}  // namespace pmsim
