// The app's Exercise panel (issue 23) driven by a script, as a student would: open their file, type
// the answers (through the keyboard and the script's `exercise answer`), save, Check, reveal; read
// back by the window's pixels (the score's badges, the reveal layer over the field, and the layer
// turning with the stage) and by the saved answers file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/base/units.h"
#include "core/exercise/exercise_files.h"
#include "core/exercise/exercise_kind.h"
#include "core/exercise/exercise_template.h"
#include "core/exercise/reveal_geometry.h"
#include "core/exercise/student_exercise.h"
#include "core/io/scene_file.h"
#include "ui/exercise_panel.h"
#include "ui/file_browser.h"
#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 1280, kH = 800;

struct Fixture {
  fs::path dir;
  std::string file;
  StudentExercise ex;
};

// A student file of the granite template in a fresh folder; its truth made in memory (the key).
// The seed is above 10^9, as pmsim-exercise draws them (scene files once refused such seeds).
Fixture granite_student(const std::string& name, bool check = true, std::uint32_t seed = 2000000000u) {
  Fixture f;
  f.dir = fs::temp_directory_path() / ("pmsim_ui_exercise_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(f.dir);
  fs::create_directories(f.dir);
  const ExerciseTemplate t = load_exercise_template("granite-minerals");
  f.ex = make_student_exercise(t, name, seed);
  nlohmann::json j = student_file_json(t, f.ex);
  j["check"] = check;
  f.file = (f.dir / (name + ".pmexercise.json")).string();
  std::ofstream(f.file) << j.dump(1);
  return f;
}

ScriptResult run(UiDriver& d, const std::string& text) { return run_script(d, parse_script(text, "test"), "test"); }

bool near(const std::uint8_t* p, const std::array<int, 3>& c, int tol) {
  return std::abs(p[0] - c[0]) + std::abs(p[1] - c[1]) + std::abs(p[2] - c[2]) <= tol;
}

// Pixels of colour `c` (to `tol`, summed over R, G, B) inside a rectangle of the window.
long count(const WindowPixels& px, const Rect& r, const std::array<int, 3>& c, int tol = 0) {
  long n = 0;
  for (int y = std::max(0, int(r.y)); y < std::min(px.height, int(r.y + r.h)); ++y)
    for (int x = std::max(0, int(r.x)); x < std::min(px.width, int(r.x + r.w)); ++x)
      n += near(&px.rgb[(std::size_t(y) * px.width + x) * 3], c, tol);
  return n;
}

// The outline pixels the reveal layer adds inside the field circle: in `on`, not in `off`.
std::vector<char> outline_mask(const WindowPixels& on, const WindowPixels& off, const Rect& f) {
  std::vector<char> m(std::size_t(on.width) * on.height, 0);
  for (int y = int(f.y); y < int(f.y + f.h); ++y)
    for (int x = int(f.x); x < int(f.x + f.w); ++x) {
      if (std::hypot(x + 0.5 - f.cx(), y + 0.5 - f.cy()) > 0.47 * f.w) continue;
      const std::size_t i = std::size_t(y) * on.width + x;
      m[i] = near(&on.rgb[i * 3], kRevealOutline, 30) && !near(&off.rgb[i * 3], kRevealOutline, 30);
    }
  return m;
}

WindowPixels shot(UiDriver& d) {
  d.frame();
  return d.read_pixels();
}

TEST(UiExercisePanel, AnswerCheckRevealSaveByScriptReadBackByPixelsAndFile) {
  const Fixture f = granite_student("ann");
  std::string log;
  auto d = HeadlessDriver::create(Scene{}, kW, kH, log);
  ASSERT_TRUE(d) << log;
  // Small flat renders: the test is about the panel, not the image.
  ScriptResult r = run(*d, "exercise open " + f.file +
                               "\nset render.width=64\nset render.height=64\nset optics.relief=off\nset render.spp=4\n");
  ASSERT_TRUE(r.ok) << r.error;
  const ExerciseSession* s = d->app().exercise();
  ASSERT_TRUE(s);
  ASSERT_EQ(s->tasks.size(), f.ex.tasks.size());
  const int n = int(s->tasks.size());
  auto truth = [&](int i) { return answer_text(f.ex.tasks[std::size_t(i)].truth.answer); };
  // The keyboard: E puts the focus in the first empty answer, Tab moves to the next one.
  r = run(*d, "key E\nwait 3\ntype " + truth(0) + "\nkey Tab\nwait 2\ntype " + truth(1) + "\nkey Enter\nwait 2\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(s->answers[0], truth(0));
  EXPECT_EQ(s->answers[1], truth(1));
  // The rest through the script, all right but the first numeric task's, 20 off the truth (toward
  // the middle of [0, 45] for an extinction angle, so that folding cannot make it right).
  int wrong = -1;
  for (int i = 0; i < n && wrong < 0; ++i)
    if (task_kind_info(f.ex.tasks[std::size_t(i)].spec.kind).numeric) wrong = i;
  ASSERT_GE(wrong, 0);
  std::string script;
  for (int i = 2; i < n; ++i) script += "exercise answer " + s->tasks[std::size_t(i)].id + " " + truth(i) + "\n";
  const double t = f.ex.tasks[std::size_t(wrong)].truth.answer.get<double>();
  script += "exercise answer " + s->tasks[std::size_t(wrong)].id + " " + std::to_string(t >= 22.5 ? t - 20 : t + 20) + "\n";
  script += "exercise save\nexercise reveal on\nexpect-error\nexercise check\nwait 2\n";
  r = run(*d, script);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_TRUE(s->graded);
  d->app().clear_error();  // the banner of the expected error would cover the field's top
  for (int i = 0; i < n; ++i) EXPECT_EQ(s->graded->tasks[std::size_t(i)].correct, i != wrong) << s->tasks[std::size_t(i)].id;

  // The score's badges: n − 1 green squares and one red in the panel.
  const Layout& l = d->app().layout();
  WindowPixels off = shot(*d);
  const long badge = long(kBadgeSize) * kBadgeSize;
  EXPECT_EQ(count(off, l.controls, kBadgeRight), (n - 1) * badge);
  EXPECT_EQ(count(off, l.controls, kBadgeWrong), badge);

  // The reveal layer: outlines, slow (red) and fast (white) directions over the field.
  r = run(*d, "exercise reveal on\n");
  ASSERT_TRUE(r.ok) << r.error;
  WindowPixels on = shot(*d);
  const std::vector<char> mask0 = outline_mask(on, off, l.field);
  long outline = 0;
  for (char c : mask0) outline += c;
  const long slow_on = count(on, l.field, kRevealSlow, 20), slow_off = count(off, l.field, kRevealSlow, 20);
  const long ind_on = count(on, l.field, kRevealIndicatrix, 30), ind_off = count(off, l.field, kRevealIndicatrix, 30);
  std::printf("outline px %ld, slow px %ld (off %ld), indicatrix px %ld (off %ld), grains %zu\n", outline, slow_on,
              slow_off, ind_on, ind_off, s->geometry->grains.size());
  EXPECT_GT(outline, 1000);
  EXPECT_GT(slow_on, slow_off + 40);
  EXPECT_GT(ind_on, ind_off + 40);

  // It follows the stage: turned 30° counter-clockwise (Shift+Left twice), the outlines are those
  // of stage 0° turned 30° about the crosshair, and the grains' slow directions turn with them.
  const RevealGeometry before = *s->geometry;
  r = run(*d, "key shift+Left\nkey shift+Left\nexercise wait\nexercise reveal off\n");
  ASSERT_TRUE(r.ok) << r.error;
  const WindowPixels off30 = shot(*d);
  r = run(*d, "exercise reveal on\n");
  ASSERT_TRUE(r.ok) << r.error;
  const WindowPixels on30 = shot(*d);
  ASSERT_NEAR(d->app().scene().stage_deg, 30.0, 1e-9);
  for (const RevealGrain& g : s->geometry->grains)
    for (const RevealGrain& g0 : before.grains)
      if (g.label == g0.label && g.slow_vibration_deg && g0.slow_vibration_deg) {
        EXPECT_NEAR(std::fmod(*g0.slow_vibration_deg + 30.0, 180.0), *g.slow_vibration_deg, 1e-6) << g.label;
      }
  const std::vector<char> mask30 = outline_mask(on30, off30, l.field);
  // Each outline pixel at 30°, turned back by 30° (screen y down), should find one at 0° within 3 px (the
  // label image's staircase is 2.1 screen pixels a step here).
  auto matched = [&](double sign) {
    long hit = 0, all = 0;
    const double c = std::cos(30.0 * kPi / 180.0), sn = sign * std::sin(30.0 * kPi / 180.0);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (!mask30[std::size_t(y) * kW + x]) continue;
        const double dx = x + 0.5 - l.field.cx(), dy = y + 0.5 - l.field.cy();
        const int x0 = int(std::floor(l.field.cx() + dx * c - dy * sn)), y0 = int(std::floor(l.field.cy() + dx * sn + dy * c));
        bool found = false;
        for (int v = -3; v <= 3 && !found; ++v)
          for (int u = -3; u <= 3 && !found; ++u)
            if (x0 + u >= 0 && x0 + u < kW && y0 + v >= 0 && y0 + v < kH) found = mask0[std::size_t(y0 + v) * kW + x0 + u];
        // Pixels turned in from outside the stage-0 field have nothing to match.
        if (std::hypot(x0 + 0.5 - l.field.cx(), y0 + 0.5 - l.field.cy()) > 0.45 * l.field.w) continue;
        hit += found, ++all;
      }
    return all ? double(hit) / all : 0.0;
  };
  const double right_way = matched(+1.0), wrong_way = matched(-1.0);
  std::printf("outline pixels at 30 deg found at 0 deg turned back: %.3f (turned the wrong way: %.3f)\n", right_way,
              wrong_way);
  EXPECT_GT(right_way, 0.8);
  EXPECT_GT(right_way, wrong_way + 0.5);

  // The saved file: every task, typed values as the grader reads them; no temporary left behind.
  const StudentAnswers saved = read_answers_file(answers_path_for(f.file));
  EXPECT_EQ(saved.student, "ann");
  ASSERT_EQ(saved.answers.size(), std::size_t(n));
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(saved.answers[std::size_t(i)].first, f.ex.tasks[std::size_t(i)].spec.id);
    EXPECT_EQ(saved.answers[std::size_t(i)].second, typed_answer(s->tasks[std::size_t(i)], s->answers[std::size_t(i)]));
  }
  EXPECT_TRUE(saved.answers[std::size_t(wrong)].second.is_number());
  EXPECT_EQ(std::distance(fs::directory_iterator(f.dir), fs::directory_iterator{}), 2);
  // Grading the saved file gives what the panel showed.
  const GradedStudent g = grade_student(key_student(f.ex), &saved);
  EXPECT_NEAR(g.score(), double(n - 1) / n, 1e-12);

  // Opened again, the answers come back from the file.
  const std::vector<ExerciseTaskView> tasks = s->tasks;
  const std::vector<std::string> typed = s->answers;
  ASSERT_TRUE(run(*d, "exercise open " + f.file + "\n").ok);
  ASSERT_NE(d->app().exercise(), nullptr);
  for (int i = 0; i < n; ++i)
    EXPECT_EQ(typed_answer(tasks[std::size_t(i)], d->app().exercise()->answers[std::size_t(i)]),
              typed_answer(tasks[std::size_t(i)], typed[std::size_t(i)]));
  fs::remove_all(f.dir);
}

TEST(UiExercisePanel, NoCheckWhenTheTemplateSaysSoAndNoRevealBeforeIt) {
  const Fixture f = granite_student("bob", false);
  std::string log;
  auto d = HeadlessDriver::create(Scene{}, kW, kH, log);
  ASSERT_TRUE(d) << log;
  const ScriptResult r = run(*d, "exercise open " + f.file +
                                     "\nset render.width=32\nset render.height=32\nset optics.relief=off\n"
                                     "exercise answer B1 quartz\nexercise check\nexpect-error\nexercise reveal on\nexpect-error\n"
                                     "exercise answer Z9 1\nexpect-error\nexercise save\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_FALSE(d->app().exercise()->graded);
  const StudentAnswers saved = read_answers_file(answers_path_for(f.file));
  const int b1 = exercise_task_index(*d->app().exercise(), "B1");
  ASSERT_GE(b1, 1);
  ASSERT_EQ(saved.answers.size(), d->app().exercise()->tasks.size());
  EXPECT_EQ(saved.answers[std::size_t(b1)].second, "quartz");
  // The file dialog's "Open exercise..." lists the exercise by its double extension, not the answers.
  std::string error;
  const std::vector<DirectoryEntry> listed = list_directory(f.dir.string(), {".pmexercise.json"}, error);
  ASSERT_EQ(listed.size(), 1u) << error;
  EXPECT_EQ(listed[0].name, "bob.pmexercise.json");
  EXPECT_TRUE(saved.answers[0].second.is_null());
  fs::remove_all(f.dir);
}

// Answers typed and never saved are written when the window closes, and when another exercise
// replaces theirs: a student loses nothing by closing the app.
TEST(UiExercisePanel, UnsavedAnswersAreSavedOnCloseAndOnOpeningAnother) {
  const Fixture a = granite_student("carol"), b = granite_student("dave");
  const std::string a_answers = answers_path_for(a.file), b_answers = answers_path_for(b.file);
  {
    std::string log;
    auto d = HeadlessDriver::create(Scene{}, kW, kH, log);
    ASSERT_TRUE(d) << log;
    const ScriptResult r = run(*d, "exercise open " + a.file +
                                       "\nset render.width=32\nset render.height=32\nset optics.relief=off\n"
                                       "exercise answer B1 quartz\nexercise open " + b.file +
                                       "\nexercise answer B1 biotite\n");
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_TRUE(fs::exists(a_answers)) << "saved when dave's exercise replaced carol's";
    EXPECT_FALSE(fs::exists(b_answers)) << "nothing written before the window closes";
  }
  ASSERT_TRUE(fs::exists(b_answers)) << "saved when the app closed";
  const StudentAnswers sa = read_answers_file(a_answers), sb = read_answers_file(b_answers);
  const auto answer = [](const StudentAnswers& s, const std::string& id) {
    for (const auto& [task, value] : s.answers)
      if (task == id) return value;
    return nlohmann::json();
  };
  EXPECT_EQ(answer(sa, "B1"), "quartz");
  EXPECT_EQ(answer(sb, "B1"), "biotite");
  fs::remove_all(a.dir);
  fs::remove_all(b.dir);
}

}  // namespace
}  // namespace pmsim::ui
