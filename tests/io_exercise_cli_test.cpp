// pmsim-exercise as a teacher scripts it (issue 23): make a class, answer from the key, grade to a
// CSV and a JSON report; a roster names the students; a student file renders with pmsim-render;
// bad input exits 2 naming the file and the key, and writes no report.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "render_cli_run.h"

namespace fs = std::filesystem;

namespace {

const std::string kExercise = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-exercise";

struct ProgramRun {
  int code;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

ProgramRun run(const std::string& program, const std::string& args, const std::string& dir) {
  const int status =
      std::system((program + " " + args + " >" + dir + "/stdout.txt 2>" + dir + "/stderr.txt").c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir + "/stdout.txt"), slurp(dir + "/stderr.txt")};
}

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// Answers for every student of a key, each from the key itself.
std::vector<std::string> answers_from_key(const std::string& dir, bool perturb_first) {
  const nlohmann::json key = nlohmann::json::parse(slurp(dir + "/class/key.json"));
  std::vector<std::string> files;
  for (const auto& s : key["students"]) {
    nlohmann::json a = {{"student", s["student"]}, {"answers", nlohmann::json::array()}};
    for (const auto& t : s["tasks"]) a["answers"].push_back({{"task", t["task"]}, {"answer", t["answer"]}});
    if (perturb_first && files.empty()) a["answers"][0]["answer"] = "halite";  // task A1: identify
    files.push_back(dir + "/" + s["student"].get<std::string>() + ".answers.json");
    write(files.back(), a.dump());
  }
  return files;
}

}  // namespace

TEST(ExerciseCli, MakeAnswerGradeRoundTrip) {
  const std::string dir = pmsim::test::cli_temp_dir("exercise_cli");
  fs::remove_all(dir + "/class");
  ProgramRun r = run(kExercise, "make granite-minerals --students 3 --out " + dir + "/class", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"student01.pmexercise.json", "student02.pmexercise.json", "student03.pmexercise.json", "key.json"})
    EXPECT_TRUE(fs::exists(dir + "/class/" + f)) << f;
  const auto files = answers_from_key(dir, true);
  std::string args = "grade " + dir + "/class/key.json";
  for (const auto& f : files) args += " " + f;
  r = run(kExercise, args + " --out " + dir + "/report.csv --json " + dir + "/report.json", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(dir + "/report.csv");
  EXPECT_EQ(csv.rfind("student,task,kind,answer,expected,correct\n", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3 * 9);  // a row per student and task
  EXPECT_NE(csv.find("student01,A1,identify,halite,biotite,false"), std::string::npos) << csv;
  const nlohmann::json report = nlohmann::json::parse(slurp(dir + "/report.json"));
  ASSERT_EQ(report["students"].size(), 3u);
  EXPECT_DOUBLE_EQ(report["students"][0]["score"].get<double>(), 8.0 / 9.0);
  EXPECT_DOUBLE_EQ(report["students"][1]["score"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(report["students"][2]["score"].get<double>(), 1.0);
}

TEST(ExerciseCli, RosterNamesAndStudentFileRenders) {
  const std::string dir = pmsim::test::cli_temp_dir("exercise_cli_roster");
  fs::remove_all(dir + "/class");
  write(dir + "/roster.txt", "# class 2B\nAda Lovelace\n\nMary Anning\n");
  ProgramRun r = run(kExercise, "make crystal-figures --roster " + dir + "/roster.txt --out " + dir + "/class", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir + "/class/Ada_Lovelace.pmexercise.json"));
  ASSERT_TRUE(fs::exists(dir + "/class/Mary_Anning.pmexercise.json"));
  const nlohmann::json f = nlohmann::json::parse(slurp(dir + "/class/Ada_Lovelace.pmexercise.json"));
  EXPECT_EQ(f["student"], "Ada Lovelace");
  EXPECT_EQ(f["scene"]["mode"], "cono");
  // pmsim-render opens a student file as its specimen.
  r = run(pmsim::test::kRenderBinary,
          dir + "/class/Ada_Lovelace.pmexercise.json --set render.width=24 --set render.height=24 --out " + dir + "/a.png",
          dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/a.png"));
}

TEST(ExerciseCli, BadInputExitsTwoNamingFileAndKeyWritingNoReport) {
  const std::string dir = pmsim::test::cli_temp_dir("exercise_cli_bad");
  fs::remove_all(dir + "/class");
  ASSERT_EQ(run(kExercise, "make schist-minerals --students 2 --out " + dir + "/class", dir).code, 0);
  const auto files = answers_from_key(dir, false);
  const std::string report = dir + "/bad_report.csv";
  // A malformed answers file: "answers" not a list.
  write(dir + "/bad.json", R"({"student": "student01", "answers": "A1=muscovite"})");
  ProgramRun r = run(kExercise, "grade " + dir + "/class/key.json " + files[1] + " " + dir + "/bad.json --out " + report, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'answers'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(report));
  // Not JSON at all; a student not in the key; an answer that is a list.
  write(dir + "/notjson.json", "{\"student\": ");
  write(dir + "/stranger.json", R"({"student": "nobody", "answers": []})");
  write(dir + "/list.json", R"({"student": "student01", "answers": [{"task": "A1", "answer": [1, 2]}]})");
  for (const auto& [file, key] : {std::pair{"notjson.json", ""}, std::pair{"stranger.json", "'student'"},
                                  std::pair{"list.json", "'answers[0].answer'"}}) {
    r = run(kExercise, "grade " + dir + "/class/key.json " + dir + "/" + file + " --out " + report, dir);
    EXPECT_EQ(r.code, 2) << file;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(key), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(report)) << file;
  }
  // An unknown template, and make without a class size.
  r = run(kExercise, "make no-such-template --students 2 --out " + dir + "/x", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no-such-template"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/x"));
  EXPECT_EQ(run(kExercise, "make granite-minerals --out " + dir + "/x", dir).code, 2);
}

TEST(ExerciseCli, IdentifyListsCandidatesWithWhy) {
  const std::string dir = pmsim::test::cli_temp_dir("exercise_cli_identify");
  ProgramRun r = run(kExercise,
                     "identify --character uniaxial --sign positive --order 1 --relief low --coloured no --json", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  bool quartz = false;
  for (const auto& c : j) {
    EXPECT_NE(c["mineral"], "calcite");  // uniaxial negative, high birefringence
    if (c["mineral"] == "quartz") quartz = !c["why"].empty();
  }
  EXPECT_TRUE(quartz) << r.out;
  r = run(kExercise, "identify --two-v 70:20", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'two-v' = 70:20"), std::string::npos) << r.err;
}
