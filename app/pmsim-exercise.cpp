// pmsim-exercise: a class exercise from a template (assets/exercises), one specimen per student,
// and the grading of the answers against the key (issue 23; formats in docs/exercises.md).
//   pmsim-exercise make TEMPLATE --students N --out DIR [--roster FILE] [--seed S]
//   pmsim-exercise grade DIR/key.json ANSWERS.json... --out report.csv [--json report.json]
//   pmsim-exercise identify [--relief low|moderate|high|very_high] [--character …] … [--json]
//   pmsim-exercise list
// Bad input exits 2 naming the file, key and value, and writes nothing.
#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "core/io/cli_policy.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/splitmix64.h"
#include "core/exercise/exercise_files.h"
#include "core/exercise/identify.h"
#include "core/io/atomic_file.h"

namespace {

// A roster name as a file name: letters, digits, '.', '-' and '_' kept, anything else '_'.
std::string file_stem(const std::string& name) {
  std::string s;
  for (unsigned char c : name) s += (std::isalnum(c) || c == '.' || c == '-' || c == '_') ? char(c) : '_';
  if (s.empty() || s[0] == '.') s = "_" + s;
  return s;
}

std::vector<std::string> read_roster(const std::string& path) {
  std::vector<std::string> names;
  std::set<std::string> stems;
  std::size_t line_no = 0;
  std::string text = pmsim::read_text_file(path, "roster");
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    std::size_t a = 0;
    while (a < line.size() && std::isspace(static_cast<unsigned char>(line[a]))) ++a;
    line = line.substr(a);
    if (line.empty() || line[0] == '#') continue;
    if (!stems.insert(file_stem(line)).second)
      throw pmsim::InputError(path, "line " + std::to_string(line_no), line,
                              "two students would share the file " + file_stem(line) + ".pmexercise.json");
    names.push_back(line);
  }
  if (names.empty()) throw pmsim::InputError(path, "", "", "the roster names no student");
  return names;
}

int make(const std::string& template_name, int students, const std::string& roster, const std::string& out_dir,
         std::uint32_t base_seed) {
  namespace fs = std::filesystem;
  const pmsim::ExerciseTemplate t = pmsim::load_exercise_template(template_name);
  std::vector<std::string> names;
  if (!roster.empty()) {
    names = read_roster(roster);
  } else {
    for (int i = 1; i <= students; ++i) {
      char b[32];
      std::snprintf(b, sizeof b, "student%02d", i);
      names.emplace_back(b);
    }
  }
  // Every exercise is made before anything is written: a template that cannot serve one student
  // leaves no half class behind.
  std::vector<std::pair<std::string, nlohmann::json>> files;
  nlohmann::json key_students = nlohmann::json::array();
  std::set<std::uint32_t> seeds;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::uint32_t seed = std::uint32_t(pmsim::splitmix64(base_seed * 0x100000001B3ull + i) & 0x7fffffffu);
    while (!seeds.insert(seed).second) seed = (seed + 1) & 0x7fffffffu;  // distinct specimens
    const pmsim::StudentExercise ex = pmsim::make_student_exercise(t, names[i], seed);
    const std::string file = file_stem(names[i]) + ".pmexercise.json";
    files.emplace_back(file, pmsim::student_file_json(t, ex));
    key_students.push_back(pmsim::key_student_json(ex, file));
  }
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw pmsim::InputError("", "--out", out_dir, "cannot create the folder: " + ec.message());
  for (const auto& [file, j] : files) pmsim::write_text_atomically((fs::path(out_dir) / file).string(), j.dump(2) + "\n");
  const nlohmann::json key = {{"template", t.name}, {"title", t.title}, {"base_seed", base_seed}, {"students", key_students}};
  pmsim::write_text_atomically((fs::path(out_dir) / "key.json").string(), key.dump(2) + "\n");
  std::cout << "wrote " << files.size() << " exercise files and key.json to " << out_dir << " (template "
            << t.name << ", " << t.tasks.size() << " tasks each)\n";
  return 0;
}

int grade(const std::string& key_path, const std::vector<std::string>& answer_paths, const std::string& csv,
          const std::string& json) {
  const auto key = pmsim::read_key_file(key_path);
  std::vector<pmsim::StudentAnswers> answers;
  for (const auto& p : answer_paths) answers.push_back(pmsim::read_answers_file(p));
  const auto graded = pmsim::grade_class(key, answers);
  pmsim::write_text_atomically(csv, pmsim::report_csv(graded));
  if (!json.empty()) pmsim::write_text_atomically(json, pmsim::report_json(graded).dump(2) + "\n");
  double mean = 0;
  for (const auto& g : graded) mean += g.score();
  std::cout << "graded " << graded.size() << " students (" << answers.size() << " answer files): mean score "
            << pmsim::number_text(graded.empty() ? 0.0 : mean / double(graded.size())) << "\n";
  return 0;
}

// The observations as CLI11 options, each parsed by core (parse_observation) so that the panel
// and the command read them alike.
struct IdentifyOptions {
  std::vector<std::pair<std::string, std::string>> given;  // (observation, value)
  bool json = false;
};

void add_identify_options(CLI::App* id, IdentifyOptions& o, std::map<std::string, std::string>& values) {
  const std::pair<const char*, const char*> obs[] = {
      {"opaque", "yes|no: black in plane and crossed light (magnetite, ilmenite)"},
      {"relief", "relief against n = 1.54: low|moderate|high|very_high"},
      {"relief-sign", "positive|negative (Becke line into or out of the grain against 1.54)"},
      {"n", "an index measured in liquids, N or LOW:HIGH"},
      {"coloured", "yes|no in plane light"},
      {"pleochroic", "yes|no"},
      {"order", "highest interference order seen (0: dark between crossed polars in every position)"},
      {"thickness", "section thickness in µm for --order (default 30)"},
      {"character", "isotropic|uniaxial|biaxial"},
      {"sign", "optic sign: positive|negative"},
      {"two-v", "2V in degrees, N or LOW:HIGH"},
      {"extinction", "parallel|inclined|symmetric"},
      {"extinction-angle", "the largest extinction angle measured (deg)"},
      {"elongation", "sign of elongation: length-slow|length-fast"},
      {"cleavages", "cleavage directions seen in one grain (0-6)"},
      {"twin", "a twin law seen (albite, carlsbad, …) or any"}};
  for (const auto& [name, help] : obs) id->add_option("--" + std::string(name), values[name], help);
  id->add_flag("--json", o.json, "print the candidates as JSON");
}

int identify(const std::map<std::string, std::string>& values, const IdentifyOptions& o, const CLI::App& id) {
  pmsim::Observations obs;
  for (const auto& [name, value] : values)
    if (id.count("--" + name) > 0) obs = pmsim::parse_observation(obs, name, value);
  const auto found = pmsim::identify(obs);
  if (o.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& c : found) j.push_back({{"mineral", c.mineral}, {"why", c.why}});
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << found.size() << " of " << pmsim::library_signatures().size() << " library minerals fit:\n";
  for (const auto& c : found) {
    std::cout << "  " << c.mineral;
    for (std::size_t i = 0; i < c.why.size(); ++i) std::cout << (i ? "; " : ": ") << c.why[i];
    std::cout << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Make class exercises from a template, one specimen per student, and grade the answers.",
               "pmsim-exercise"};
  pmsim::cli::last_value_wins(app);
  app.require_subcommand(1);
  std::string template_name, out_dir, roster, key_path, csv, json;
  int students = 0;
  std::uint32_t seed = 1;
  std::vector<std::string> answers;
  CLI::App* mk = app.add_subcommand("make", "write DIR/<student>.pmexercise.json per student and DIR/key.json");
  mk->add_option("template", template_name, "template name in assets/exercises, or a file")->required();
  mk->add_option("--students", students, "number of students (student01, student02, …)")->check(CLI::Range(1, 1000));
  mk->add_option("--roster", roster, "file with one student name a line (instead of --students)");
  mk->add_option("--out", out_dir, "folder to write to")->required();
  mk->add_option("--seed", seed, "class seed: another seed, another set of specimens (default 1)");
  CLI::App* gr = app.add_subcommand("grade", "grade answer files against the key: CSV rows and a JSON with scores");
  gr->add_option("key", key_path, "key.json written by make")->required();
  gr->add_option("answers", answers, "answer files {\"student\", \"answers\": [{\"task\", \"answer\"}]}");
  gr->add_option("--out", csv, "CSV report: student,task,kind,answer,expected,correct")->required();
  gr->add_option("--json", json, "JSON report with each student's score in [0, 1]");
  CLI::App* ls = app.add_subcommand("list", "list the shipped templates");
  CLI::App* id = app.add_subcommand(
      "identify", "list the library minerals consistent with what was observed, each with why (a determinative aid)");
  IdentifyOptions id_options;
  std::map<std::string, std::string> observed;
  add_identify_options(id, id_options, observed);
  pmsim::cli::parse_or_exit(app, argc, argv);
  try {
    if (*mk) {
      if ((students > 0) == !roster.empty()) pmsim::cli::usage_error("pmsim-exercise", "make takes --students N or --roster FILE");
      return make(template_name, students, roster, out_dir, seed);
    }
    if (*gr) return grade(key_path, answers, csv, json);
    if (*id) return identify(observed, id_options, *id);
    if (*ls) {
      for (const auto& n : pmsim::exercise_template_names()) {
        const auto t = pmsim::load_exercise_template(n);
        std::cout << n << "\t" << t.title << " (" << t.tasks.size() << " tasks)\n";
      }
      return 0;
    }
  } catch (const pmsim::InputError& e) {
    std::cerr << "pmsim-exercise: " << e.what() << "\n";
    return pmsim::cli::kUsageErrorExitCode;
  } catch (const std::exception& e) {
    std::cerr << "pmsim-exercise: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
