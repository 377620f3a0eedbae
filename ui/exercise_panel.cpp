// The Exercise tab: a student's tasks, their answers, Check and the graded result (issue 23).
#include "ui/exercise_panel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <imgui.h>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/crystal/crystal.h"
#include "core/io/atomic_file.h"
#include "core/io/scene_file.h"
#include "ui/app.h"

namespace pmsim::ui {
namespace {

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

ImVec4 colour(const std::array<int, 3>& c) { return ImVec4(c[0] / 255.f, c[1] / 255.f, c[2] / 255.f, 1.f); }

template <typename T>
bool ready(const std::future<T>& f) {
  return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

const std::vector<std::string>& library_minerals() {
  static const std::vector<std::string> names = [] {
    try {
      return mineral_names();
    } catch (const std::exception&) {
      return std::vector<std::string>{};
    }
  }();
  return names;
}

// The text field of an answer, with the kind's words in a combo beside it for the mouse.
bool answer_field(const ExerciseTaskView& t, std::string& text, bool focus) {
  char buffer[256];
  std::strncpy(buffer, text.c_str(), sizeof buffer - 1);
  buffer[sizeof buffer - 1] = '\0';
  const bool words = !t.choices.empty();
  ImGui::PushItemWidth(ImGui::GetContentRegionAvail().x - (words ? 28.f : 0.f));
  if (focus) ImGui::SetKeyboardFocusHere();
  const char* hint = !t.unit.empty() ? t.unit.c_str() : words ? "type or pick" : "answer";
  bool edited = ImGui::InputTextWithHint(("##answer_" + t.id).c_str(), hint, buffer, sizeof buffer);
  ImGui::PopItemWidth();
  if (edited) text = buffer;
  if (words) {
    ImGui::SameLine(0, 4);
    if (ImGui::BeginCombo(("##choices_" + t.id).c_str(), nullptr, ImGuiComboFlags_NoPreview)) {
      for (const std::string& c : t.choices)
        if (ImGui::Selectable(c.c_str(), c == text)) {
          text = c;
          edited = true;
        }
      ImGui::EndCombo();
    }
  }
  return edited;
}

}  // namespace

ExerciseSession read_exercise_session(const std::string& path) {
  ExerciseSession s;
  s.file = read_student_file(path);
  const nlohmann::json j = read_json_file(path, "exercise file");
  const JsonReader r(j, path);
  s.title = r.get_or<std::string>("title", "");
  s.description = r.get_or<std::string>("description", "");
  s.check_allowed = r.get_or<bool>("check", true);
  s.answers_path = answers_path_for(path);
  for (const JsonReader& t : r.objects("tasks", 1)) {
    ExerciseTaskView v;
    v.id = t.require<std::string>("task");
    const auto kind = find_task_kind(t.require<std::string>("kind"));
    if (!kind) t.fail("kind", "expected one of " + task_kind_list());
    v.kind = *kind;
    v.question = t.get_or<std::string>("question", task_kind_info(v.kind).question);
    v.where = t.get_or<std::string>("where", "");
    v.unit = t.get_or<std::string>("unit", "");
    v.choices = task_kind_info(v.kind).choices;
    if (v.kind == TaskKind::Identify) v.choices = library_minerals();
    if (const nlohmann::json* st = t.find("stage"); st && st->is_object())
      v.stage_mm = std::array<double, 2>{st->value("x_mm", 0.0), st->value("y_mm", 0.0)};
    // "grain A: …": the template's grain id, for the markers on the field.
    if (v.where.rfind("grain ", 0) == 0) v.grain = v.where.substr(6, v.where.find(':') - 6);
    s.tasks.push_back(std::move(v));
  }
  s.answers.assign(s.tasks.size(), "");
  std::error_code ec;
  if (std::filesystem::exists(s.answers_path, ec)) {
    const StudentAnswers saved = read_answers_file(s.answers_path);
    for (const auto& [task, value] : saved.answers)
      if (const int i = exercise_task_index(s, task); i >= 0) s.answers[std::size_t(i)] = answer_text(value);
    s.saved_at = s.answers_path;
  }
  return s;
}

nlohmann::json typed_answer(const ExerciseTaskView& task, const std::string& text) {
  const std::string t = trimmed(text);
  if (t.empty()) return nullptr;
  if (task_kind_info(task.kind).numeric) {
    try {
      std::size_t used = 0;
      const double v = std::stod(t, &used);
      // Whole numbers as integers (an order "2", not "2.0", in the answers file).
      if (used == t.size() && std::isfinite(v))
        return v == std::floor(v) && std::fabs(v) < 1e15 ? nlohmann::json(static_cast<long long>(v)) : nlohmann::json(v);
    } catch (const std::exception&) {
    }
  }
  return t;
}

StudentAnswers session_answers(const ExerciseSession& s) {
  StudentAnswers a;
  a.path = s.answers_path;
  a.student = s.file.student;
  for (std::size_t i = 0; i < s.tasks.size(); ++i) a.answers.emplace_back(s.tasks[i].id, typed_answer(s.tasks[i], s.answers[i]));
  return a;
}

int exercise_task_index(const ExerciseSession& s, const std::string& id) {
  for (std::size_t i = 0; i < s.tasks.size(); ++i)
    if (s.tasks[i].id == id) return static_cast<int>(i);
  return -1;
}

// --- the App's side ------------------------------------------------------------------------

bool App::open_exercise(const std::string& path, bool load_specimen) {
  std::unique_ptr<ExerciseSession> session;
  Scene loaded;
  try {
    session = std::make_unique<ExerciseSession>(read_exercise_session(path));
    if (load_specimen) loaded = load_scene_file(path);
  } catch (const std::exception& e) {
    fail(e.what());
    ++counters_.rejected;
    return false;
  }
  if (load_specimen && !commit(loaded)) return false;
  // The exercise it replaces keeps its typed answers (a student switching files loses none).
  if (exercise_ && exercise_->unsaved) exercise_save();
  scene_path_ = path;
  session->select_tab = true;
  exercise_ = std::move(session);
  note("opened the exercise " + path);
  return true;
}

std::string App::exercise_path_or(const std::string& fallback) const {
  return exercise_ ? exercise_->file.path : fallback;
}

bool App::exercise_answer(const std::string& task, const std::string& text) {
  const int i = exercise_ ? exercise_task_index(*exercise_, task) : -1;
  if (i < 0) {
    fail(exercise_ ? "exercise: no task '" + task + "' in " + exercise_->file.path : "exercise: none is open");
    return false;
  }
  exercise_->answers[std::size_t(i)] = text;
  exercise_->unsaved = true;
  return true;
}

bool App::exercise_check() {
  if (!exercise_) {
    fail("exercise: none is open");
    return false;
  }
  ExerciseSession& s = *exercise_;
  if (!s.check_allowed) {
    fail(s.file.path + ": this exercise is graded by the teacher (its template says \"check\": false)");
    return false;
  }
  if (s.check_job.valid()) return true;  // one at a time: the Check in flight grades what it was given
  s.check_job = std::async(std::launch::async, [file = s.file, truth = s.truth, answers = session_answers(s)] {
    ExerciseSession::Checked c;
    try {
      c.truth = truth ? truth
                      : std::make_shared<const StudentExercise>(make_student_exercise(
                            load_exercise_template(file.template_name), file.student, file.seed));
      c.graded = grade_student(key_student(*c.truth, file.path), &answers);
    } catch (const std::exception& e) {
      c.error = e.what();
    }
    return c;
  });
  return true;
}

bool App::exercise_checking() const { return exercise_ && exercise_->check_job.valid(); }

bool App::exercise_reveal(bool on) {
  if (!exercise_) {
    fail("exercise: none is open");
    return false;
  }
  if (on && !exercise_->graded) {
    fail("exercise: the reveal layer shows the answers: Check first");
    return false;
  }
  exercise_->reveal = on;
  return true;
}

bool App::exercise_reveal_ready() const {
  return exercise_ && exercise_->reveal && !exercise_->geometry_job.valid() &&
         exercise_->geometry_generation == generation_;
}

bool App::exercise_save() {
  if (!exercise_) {
    fail("exercise: none is open");
    return false;
  }
  ExerciseSession& s = *exercise_;
  try {
    write_text_atomically(s.answers_path, answers_json(session_answers(s)).dump(2) + "\n");
  } catch (const std::exception& e) {
    fail(e.what());
    return false;
  }
  s.unsaved = false;
  s.saved_at = s.answers_path;
  note("answers saved to " + s.answers_path);
  return true;
}

bool App::exercise_goto(const std::string& task) {
  const int i = exercise_ ? exercise_task_index(*exercise_, task) : -1;
  if (i < 0 || !exercise_->tasks[std::size_t(i)].stage_mm) {
    fail(i < 0 ? "exercise: no task '" + task + "'" : "exercise: task " + task + " is about the figure, not a grain");
    return false;
  }
  Scene s = scene_;
  s.stage.x_mm = (*exercise_->tasks[std::size_t(i)].stage_mm)[0];
  s.stage.y_mm = (*exercise_->tasks[std::size_t(i)].stage_mm)[1];
  return commit(s);
}

void App::exercise_action(Action action) {
  if (!exercise_) return;  // the exercise keys do nothing without an exercise
  ExerciseSession& s = *exercise_;
  switch (action) {
    case Action::ExerciseFocus: {
      s.select_tab = true;
      s.focus_task = 0;
      for (std::size_t i = 0; i < s.answers.size(); ++i)
        if (trimmed(s.answers[i]).empty()) {
          s.focus_task = static_cast<int>(i);
          break;
        }
      break;
    }
    case Action::ExerciseCheck:
      exercise_check();
      break;
    case Action::ExerciseSave:
      exercise_save();
      break;
    case Action::ExerciseReveal:
      exercise_reveal(!s.reveal);
      break;
    default:
      break;
  }
}

void App::poll_exercise() {
  if (!exercise_) return;
  ExerciseSession& s = *exercise_;
  if (ready(s.check_job)) {
    ExerciseSession::Checked c = s.check_job.get();
    if (!c.error.empty()) {
      fail(c.error);
    } else {
      s.truth = c.truth;
      s.graded = std::move(c.graded);
    }
  }
  if (ready(s.geometry_job)) {
    try {
      s.geometry = s.geometry_job.get();
      s.geometry_error.clear();
    } catch (const std::exception& e) {
      s.geometry.reset();
      s.geometry_error = e.what();
    }
    s.geometry_generation = s.job_generation;
  }
  // The layer follows the scene: a new computation for each accepted scene (stage turned or moved).
  if (s.reveal && !s.geometry_job.valid() && s.geometry_generation != generation_) {
    s.job_generation = generation_;
    s.geometry_job = std::async(std::launch::async, [scene = scene_] { return reveal_geometry(scene); });
  }
}

void App::draw_exercise_tab(Scene& edit, bool& changed) {
  ExerciseSession& s = *exercise_;
  ImGui::PushTextWrapPos(0);
  ImGui::TextUnformatted(s.title.c_str());
  ImGui::TextDisabled("%s, %s", s.file.student.c_str(), std::filesystem::path(s.file.path).filename().c_str());
  ImGui::PopTextWrapPos();
  if (ImGui::CollapsingHeader("Instructions")) ImGui::TextWrapped("%s", s.description.c_str());
  ImGui::BeginDisabled(!s.check_allowed || s.check_job.valid());
  if (ImGui::Button(s.check_job.valid() ? "Checking..." : "Check (F4)")) exercise_check();
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button(s.unsaved ? "Save answers* (Ctrl+E)" : "Save answers (Ctrl+E)")) exercise_save();
  if (!s.check_allowed) ImGui::TextDisabled("graded by your teacher: no Check");
  if (s.graded) {
    bool reveal = s.reveal;
    if (ImGui::Checkbox("Reveal layer (R)", &reveal)) exercise_reveal(reveal);
    if (s.reveal && !s.geometry_error.empty()) ImGui::TextWrapped("reveal: %s", s.geometry_error.c_str());
    if (s.reveal && s.geometry && s.geometry->figure.empty()) {
      // The legend of the layer's colours (reveal_layer.cpp).
      ImGui::TextColored(colour(kRevealOutline), "outlines");
      ImGui::SameLine();
      ImGui::TextColored(colour(kRevealSlow), "slow");
      ImGui::SameLine();
      ImGui::TextColored(colour(kRevealFast), "fast");
      ImGui::SameLine();
      ImGui::TextColored(colour(kRevealCleavage), "cleavage");
      ImGui::TextColored(colour(kRevealIndicatrix), "indicatrix section (flattening x10)");
    }
    draw_exercise_results();
  }
  if (ImGui::SmallButton("Reload the specimen")) load_scene(s.file.path);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the student file's scene again (answers are kept)");
  ImGui::Separator();
  ImGui::BeginChild("##tasks", ImVec2(0, 0), false);
  for (int i = 0; i < static_cast<int>(s.tasks.size()); ++i) draw_exercise_task(i, edit, changed);
  ImGui::EndChild();
  s.focus_task = -1;
}

void App::draw_exercise_results() {
  const ExerciseSession& s = *exercise_;
  const GradedStudent& g = *s.graded;
  const int right = static_cast<int>(std::count_if(g.tasks.begin(), g.tasks.end(), [](const auto& t) { return t.correct; }));
  ImGui::Text("Score %d / %d", right, static_cast<int>(g.tasks.size()));
  // One square per task, in task order: green right, red wrong (what the tests count).
  ImDrawList* draw = ImGui::GetWindowDrawList();
  ImGui::SameLine();
  const ImVec2 o = ImGui::GetCursorScreenPos();
  const float step = kBadgeSize + 4.f, y = o.y + (ImGui::GetTextLineHeight() - kBadgeSize) / 2;
  for (std::size_t i = 0; i < g.tasks.size(); ++i) {
    const auto& c = g.tasks[i].correct ? kBadgeRight : kBadgeWrong;
    const ImVec2 a(std::floor(o.x + i * step), std::floor(y));
    draw->AddRectFilled(a, ImVec2(a.x + kBadgeSize, a.y + kBadgeSize), IM_COL32(c[0], c[1], c[2], 255));
  }
  ImGui::Dummy(ImVec2(step * g.tasks.size(), ImGui::GetTextLineHeight()));
}

void App::draw_exercise_task(int i, Scene& edit, bool& changed) {
  ExerciseSession& s = *exercise_;
  const ExerciseTaskView& t = s.tasks[std::size_t(i)];
  ImGui::PushID(i);
  ImGui::Separator();
  ImGui::Text("%s", t.id.c_str());
  ImGui::SameLine();
  ImGui::PushTextWrapPos(0);
  ImGui::TextUnformatted(t.question.c_str());
  ImGui::PopTextWrapPos();
  if (t.stage_mm) {
    if (ImGui::SmallButton("Go to the grain")) {
      edit.stage.x_mm = (*t.stage_mm)[0];
      edit.stage.y_mm = (*t.stage_mm)[1];
      changed = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", t.where.c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("x %.3f, y %.3f mm", (*t.stage_mm)[0], (*t.stage_mm)[1]);
  } else {
    ImGui::TextDisabled("%s", t.where.c_str());
  }
  if (answer_field(t, s.answers[std::size_t(i)], s.focus_task == i)) s.unsaved = true;
  if (s.graded) {
    for (const GradedTask& g : s.graded->tasks) {
      if (g.task != t.id) continue;
      ImGui::TextColored(colour(g.correct ? std::array<int, 3>{90, 215, 120} : std::array<int, 3>{240, 110, 100}),
                         "%s", g.correct ? "right" : "wrong");
      ImGui::SameLine();
      std::string truth = "true: " + answer_text(g.expected);
      if (g.tolerance && *g.tolerance > 0) {
        char tol[48];
        std::snprintf(tol, sizeof tol, " (within %g%s%s)", *g.tolerance, t.unit.empty() ? "" : " ", t.unit.c_str());
        truth += tol;
      } else if (!t.unit.empty()) {
        truth += " " + t.unit;
      }
      ImGui::TextUnformatted(truth.c_str());
      ImGui::PushTextWrapPos(0);
      ImGui::TextDisabled("%s", g.explanation.c_str());
      ImGui::PopTextWrapPos();
    }
  }
  ImGui::PopID();
}

}  // namespace pmsim::ui
