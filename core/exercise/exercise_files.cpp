#include "core/exercise/exercise_files.h"

#include <map>
#include <set>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/exercise/colour_words.h"
#include "core/io/scene_file.h"

namespace pmsim {

namespace {

constexpr int kFormat = 1;

nlohmann::json tolerance_json(const std::optional<double>& t) { return t ? nlohmann::json(*t) : nlohmann::json(nullptr); }

// RFC 4180: a field with a comma, quote or line break is quoted, its quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// A value of an answer: a number or a string (lists and objects are no answer of any kind).
nlohmann::json answer_value(const JsonReader& r, std::string_view key) {
  const nlohmann::json* v = r.find(key);
  if (!v) r.fail(key, "missing (write null for a task not answered)");
  if (!(v->is_null() || v->is_string() || v->is_number())) r.fail(key, *v, "expected a number, a string or null");
  if (v->is_number() && !std::isfinite(v->get<double>())) r.fail(key, *v, "expected a finite number");
  return *v;
}

}  // namespace

bool is_student_file(const nlohmann::json& j) {
  return j.is_object() && j.contains("type") && j["type"].is_string() && j["type"] == "pmexercise";
}

nlohmann::json student_file_json(const ExerciseTemplate& t, const StudentExercise& ex) {
  nlohmann::json tasks = nlohmann::json::array();
  for (const StudentTask& task : ex.tasks) {
    const TaskKindInfo& info = task_kind_info(task.spec.kind);
    nlohmann::json j = {{"task", task.spec.id},
                        {"kind", info.name},
                        {"question", task.spec.question.empty() ? info.question : task.spec.question},
                        {"where", task.where}};
    if (*info.unit) j["unit"] = info.unit;
    if (!info.choices.empty()) j["choices"] = info.choices;
    if (task.spec.kind == TaskKind::Pleochroism) {
      nlohmann::json words = nlohmann::json::array();
      for (const ColourWord& w : colour_words()) words.push_back(w.word);
      j["choices"] = words;  // one for each of X, Y, Z
    }
    if (task.stage_mm) j["stage"] = {{"x_mm", (*task.stage_mm)[0]}, {"y_mm", (*task.stage_mm)[1]}};
    tasks.push_back(std::move(j));
  }
  return {{"type", "pmexercise"},        {"format", kFormat},   {"student", ex.student},
          {"template", t.name},          {"title", t.title},    {"description", t.description},
          {"seed", ex.seed},             {"check", t.check_allowed},
          {"scene", scene_to_json(ex.scene)}, {"tasks", tasks}};
}

StudentFile read_student_file(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "exercise file");
  const JsonReader r(j, path);
  if (!is_student_file(j)) r.fail("type", "an exercise file has \"type\": \"pmexercise\"");
  StudentFile f;
  f.path = path;
  f.student = r.require<std::string>("student");
  f.template_name = r.require<std::string>("template");
  f.seed = std::uint32_t(r.require<int>("seed", Range::at_least(0)));
  f.scene = r.object("scene").node();
  return f;
}

nlohmann::json key_student_json(const StudentExercise& ex, const std::string& exercise_file) {
  nlohmann::json tasks = nlohmann::json::array();
  for (const StudentTask& t : ex.tasks) {
    nlohmann::json j = {{"task", t.spec.id},
                        {"kind", task_kind_info(t.spec.kind).name},
                        {"answer", t.truth.answer},
                        {"tolerance", task_kind_info(t.spec.kind).numeric
                                          ? nlohmann::json(t.spec.tolerance.value_or(task_kind_info(t.spec.kind).default_tolerance))
                                          : nlohmann::json(nullptr)},
                        {"explanation", t.truth.explanation},
                        {"where", t.where},
                        {"grain", t.grain_label}};
    if (!t.truth.extinction_stage_deg.empty()) j["extinction_stage_deg"] = t.truth.extinction_stage_deg;
    tasks.push_back(std::move(j));
  }
  return {{"student", ex.student}, {"exercise", exercise_file}, {"seed", ex.seed}, {"tasks", tasks}};
}

std::vector<KeyStudent> read_key_file(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "exercise key");
  const JsonReader root(j, path);
  std::vector<KeyStudent> out;
  std::set<std::string> seen;
  for (const JsonReader& s : root.objects("students", 1)) {
    KeyStudent k{s.require<std::string>("student"), s.get_or<std::string>("exercise", ""), {}};
    if (!seen.insert(k.student).second) s.fail("student", "a student appears twice in the key");
    for (const JsonReader& t : s.objects("tasks", 1)) {
      KeyTask kt;
      kt.task = t.require<std::string>("task");
      const std::string kind = t.require<std::string>("kind");
      const auto kk = find_task_kind(kind);
      if (!kk) t.fail("kind", "expected one of " + task_kind_list());
      kt.kind = *kk;
      kt.answer = answer_value(t, "answer");
      if (const nlohmann::json* tol = t.find("tolerance"); tol && !tol->is_null())
        kt.tolerance = t.require<double>("tolerance", Range::at_least(0.0));
      kt.explanation = t.get_or<std::string>("explanation", "");
      k.tasks.push_back(std::move(kt));
    }
    out.push_back(std::move(k));
  }
  return out;
}

KeyStudent key_student(const StudentExercise& ex, const std::string& exercise_file) {
  KeyStudent k{ex.student, exercise_file, {}};
  for (const StudentTask& t : ex.tasks)
    k.tasks.push_back(KeyTask{t.spec.id, t.spec.kind, t.truth.answer,
                              task_kind_info(t.spec.kind).numeric
                                  ? std::optional<double>(t.spec.tolerance.value_or(task_kind_info(t.spec.kind).default_tolerance))
                                  : std::nullopt,
                              t.truth.explanation});
  return k;
}

std::string answers_path_for(const std::string& student_file) {
  std::string stem = student_file;
  for (const char* suffix : {".pmexercise.json", ".json"})
    if (stem.size() > std::string_view(suffix).size() && stem.ends_with(suffix)) {
      stem.resize(stem.size() - std::string_view(suffix).size());
      break;
    }
  return stem + ".answers.json";
}

StudentAnswers read_answers_file(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "answers file");
  const JsonReader root(j, path);
  StudentAnswers a;
  a.path = path;
  a.student = root.require<std::string>("student");
  const nlohmann::json* list = root.find("answers");
  if (!list) root.fail("answers", "missing: the list of {\"task\", \"answer\"}");
  if (!list->is_array()) root.fail("answers", *list, "expected a list of {\"task\", \"answer\"}");
  std::set<std::string> tasks;
  for (const JsonReader& r : root.objects("answers")) {
    const std::string task = r.require<std::string>("task");
    if (!tasks.insert(task).second) r.fail("task", "answered twice");
    a.answers.emplace_back(task, answer_value(r, "answer"));
  }
  return a;
}

nlohmann::json answers_json(const StudentAnswers& a) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [task, answer] : a.answers) list.push_back({{"task", task}, {"answer", answer}});
  return {{"student", a.student}, {"answers", list}};
}

double GradedStudent::score() const {
  if (tasks.empty()) return 0.0;
  std::size_t right = 0;
  for (const auto& t : tasks) right += t.correct ? 1 : 0;
  return double(right) / double(tasks.size());
}

GradedStudent grade_student(const KeyStudent& key, const StudentAnswers* answers) {
  GradedStudent g{key.student, answers != nullptr, {}};
  for (const KeyTask& t : key.tasks) {
    GradedTask r{key.student, t.task, t.kind, std::nullopt, t.answer, t.tolerance, false, t.explanation};
    if (answers)
      for (const auto& [task, value] : answers->answers)
        if (task == t.task && !value.is_null()) r.answer = value;
    r.correct = r.answer && answer_correct(t.kind, *r.answer, t.answer, t.tolerance);
    g.tasks.push_back(std::move(r));
  }
  return g;
}

std::vector<GradedStudent> grade_class(const std::vector<KeyStudent>& key, const std::vector<StudentAnswers>& answers) {
  std::map<std::string, const StudentAnswers*> by_student;
  for (const StudentAnswers& a : answers) {
    if (std::none_of(key.begin(), key.end(), [&](const KeyStudent& k) { return k.student == a.student; }))
      throw InputError(a.path, "student", a.student, "no such student in the key");
    if (!by_student.emplace(a.student, &a).second)
      throw InputError(a.path, "student", a.student, "answered twice: also in " + by_student[a.student]->path);
  }
  std::vector<GradedStudent> out;
  for (const KeyStudent& k : key) {
    const auto it = by_student.find(k.student);
    out.push_back(grade_student(k, it == by_student.end() ? nullptr : it->second));
  }
  return out;
}

std::string answer_text(const std::optional<nlohmann::json>& v) {
  if (!v || v->is_null()) return "";
  if (v->is_string()) return v->get<std::string>();
  if (v->is_number()) return number_text(v->get<double>());
  return v->dump();
}

std::string report_csv(const std::vector<GradedStudent>& graded) {
  std::string out = "student,task,kind,answer,expected,correct\n";
  for (const GradedStudent& s : graded)
    for (const GradedTask& t : s.tasks)
      out += csv_field(t.student) + "," + csv_field(t.task) + "," + task_kind_info(t.kind).name + "," +
             csv_field(answer_text(t.answer)) + "," + csv_field(answer_text(t.expected)) + "," +
             (t.correct ? "true" : "false") + "\n";
  return out;
}

nlohmann::json report_json(const std::vector<GradedStudent>& graded) {
  nlohmann::json students = nlohmann::json::array();
  double sum = 0.0;
  for (const GradedStudent& s : graded) {
    nlohmann::json tasks = nlohmann::json::array();
    std::size_t right = 0;
    for (const GradedTask& t : s.tasks) {
      right += t.correct ? 1 : 0;
      tasks.push_back({{"task", t.task},
                       {"kind", task_kind_info(t.kind).name},
                       {"answer", t.answer ? *t.answer : nlohmann::json(nullptr)},
                       {"expected", t.expected},
                       {"tolerance", tolerance_json(t.tolerance)},
                       {"correct", t.correct},
                       {"explanation", t.explanation}});
    }
    sum += s.score();
    students.push_back({{"student", s.student},
                        {"submitted", s.submitted},
                        {"score", s.score()},
                        {"correct", right},
                        {"tasks", tasks}});
  }
  return {{"students", students}, {"mean_score", graded.empty() ? 0.0 : sum / double(graded.size())}};
}

}  // namespace pmsim
