#include "core/exercise/exercise_kind.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/base/input_error.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_series.h"
#include "core/exercise/colour_words.h"

namespace pmsim {

namespace {

std::string lower_trimmed(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  std::string out;
  for (std::size_t i = a; i < b; ++i) {
    const char c = char(std::tolower(static_cast<unsigned char>(s[i])));
    // Runs of blanks, hyphens and underscores are one separator: "length slow" = "length-slow".
    const bool sep = c == ' ' || c == '-' || c == '_' || c == '\t';
    if (sep) {
      if (!out.empty() && out.back() != '-') out += '-';
    } else {
      out += c;
    }
  }
  if (out.empty() && a < b) return std::string(s.substr(a, b - a));  // a lone "-": a sign, not a separator
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out;
}

// The words a kind accepts besides its own choices, each to the choice it means. Sign of
// elongation: length-slow is positive elongation (Nesse 2012 §7.9).
std::string synonym(TaskKind kind, const std::string& w) {
  const auto is = [&](std::initializer_list<const char*> l) {
    for (const char* x : l)
      if (w == x) return true;
    return false;
  };
  switch (kind) {
    case TaskKind::SignOfElongation:
      if (is({"length-slow", "slow", "positive", "+", "positive-elongation"})) return "length-slow";
      if (is({"length-fast", "fast", "negative", "-", "negative-elongation"})) return "length-fast";
      break;
    case TaskKind::OpticSign:
      if (is({"positive", "+", "pos"})) return "positive";
      if (is({"negative", "-", "neg"})) return "negative";
      break;
    case TaskKind::ReliefVsMedium:
      if (is({"higher", "high", "positive", "+", "greater"})) return "higher";
      if (is({"lower", "low", "negative", "-", "less"})) return "lower";
      if (is({"matched", "match", "equal", "same", "none"})) return "matched";
      break;
    case TaskKind::ExtinctionType:
      if (is({"parallel", "straight"})) return "parallel";
      if (is({"inclined", "oblique"})) return "inclined";
      if (is({"symmetric", "symmetrical"})) return "symmetric";
      break;
    case TaskKind::OpticCharacter:
      if (is({"uniaxial", "biaxial", "isotropic"})) return w;
      break;
    case TaskKind::TwinLaw: {
      std::string s = w;
      for (const char* tail : {"-twins", "-twin", "-law"})
        if (s.size() > std::string_view(tail).size() && s.ends_with(tail)) s.resize(s.size() - std::string_view(tail).size());
      return s;
    }
    default:
      break;
  }
  return "";
}

// The three words of a pleochroism answer, each in lower_trimmed's spelling; empty unless three.
std::vector<std::string> colour_triple(const std::string& answer) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : answer + ",") {
    if (c == ',' || c == '/' || c == ';') {
      out.push_back(lower_trimmed(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (out.size() != 3 || std::any_of(out.begin(), out.end(), [](const std::string& w) { return w.empty(); })) return {};
  return out;
}

bool colour_word_close(const std::string& given, const std::string& expected) {
  if (given == expected) return true;
  for (const ColourWord& w : colour_words())
    if (lower_trimmed(w.word) == expected) {
      const auto ranked = nearest_colour_words(w.lab);  // ranked[0] is the word itself
      return ranked.size() > 1 && lower_trimmed(ranked[1]) == given;
    }
  return false;
}

}  // namespace

const std::vector<TaskKindInfo>& task_kinds() {
  static const std::vector<TaskKindInfo> kinds = {
      {TaskKind::Identify, "identify", false, 0, "", {}, "Which mineral is it?"},
      {TaskKind::ExtinctionAngle, "extinction_angle", true, 3.0, "deg", {},
       "Extinction angle to the cleavage trace (or the elongation), in degrees"},
      {TaskKind::ExtinctionType, "extinction_type", false, 0, "", {"parallel", "inclined", "symmetric"},
       "Extinction type"},
      {TaskKind::SignOfElongation, "sign_of_elongation", false, 0, "", {"length-slow", "length-fast"},
       "Sign of elongation"},
      {TaskKind::OpticCharacter, "optic_character", false, 0, "", {"uniaxial", "biaxial", "isotropic"},
       "Uniaxial or biaxial?"},
      {TaskKind::OpticSign, "optic_sign", false, 0, "", {"positive", "negative"}, "Optic sign"},
      {TaskKind::TwoV, "two_v", true, 8.0, "deg", {}, "2V, in degrees"},
      {TaskKind::MaxInterferenceOrder, "max_interference_order", true, 0.0, "", {},
       "Highest interference order the mineral shows in this section (1, 2, 3, …)"},
      {TaskKind::Birefringence, "birefringence", true, 0.004, "", {},
       "Birefringence (n_gamma - n_alpha) from the highest colour and the thickness"},
      {TaskKind::ReliefVsMedium, "relief_vs_medium", false, 0, "", {"higher", "lower", "matched"},
       "Is the grain's index higher or lower than the medium's (Becke line)?"},
      {TaskKind::TwinLaw, "twin_law", false, 0, "", {}, "Twin law"},
      {TaskKind::Pleochroism, "pleochroism", false, 0, "", {},
       "Colours in plane light with X, Y and Z along the polarizer (three colour words, X, Y, Z)"},
  };
  return kinds;
}

const TaskKindInfo& task_kind_info(TaskKind kind) {
  for (const auto& k : task_kinds())
    if (k.kind == kind) return k;
  return task_kinds().front();
}

std::optional<TaskKind> find_task_kind(std::string_view name) {
  std::string n;
  for (char c : name) n += char(std::tolower(static_cast<unsigned char>(c)));
  for (const auto& k : task_kinds())
    if (n == k.name) return k.kind;
  return std::nullopt;
}

std::string task_kind_list() {
  std::string all;
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on literal + std::string.
  for (const auto& k : task_kinds()) {
    if (!all.empty()) all += '|';
    all += k.name;
  }
  return all;
}

double folded_extinction_angle_deg(double deg) {
  double a = std::fmod(deg, 90.0);
  if (a < 0) a += 90.0;
  return a > 45.0 ? 90.0 - a : a;
}

std::optional<nlohmann::json> normalized_answer(TaskKind kind, const nlohmann::json& answer) {
  const TaskKindInfo& info = task_kind_info(kind);
  if (info.numeric) {
    if (answer.is_number()) {
      const double v = answer.get<double>();
      return std::isfinite(v) ? std::optional<nlohmann::json>(v) : std::nullopt;
    }
    if (!answer.is_string()) return std::nullopt;
    const std::string s = answer.get<std::string>();
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    while (end && *end && std::isspace(static_cast<unsigned char>(*end))) ++end;
    if (s.empty() || !end || *end || !std::isfinite(v)) return std::nullopt;
    return nlohmann::json(v);
  }
  if (!answer.is_string()) return std::nullopt;
  const std::string w = lower_trimmed(answer.get<std::string>());
  if (w.empty()) return std::nullopt;
  if (kind == TaskKind::Identify) {
    try {
      // A series answer is right whatever composition is written: the section's
      // "plagioclase:An32" is plagioclase to a student.
      return nlohmann::json(series_name(canonical_mineral_name(answer.get<std::string>())));
    } catch (const InputError&) {
      return nlohmann::json(w);  // not a library mineral: wrong, but it is an answer
    }
  }
  const std::string s = synonym(kind, w);
  if (s.empty()) return nlohmann::json(w);
  return nlohmann::json(s);
}

bool answer_correct(TaskKind kind, const nlohmann::json& answer, const nlohmann::json& expected,
                    std::optional<double> tolerance) {
  const auto a = normalized_answer(kind, answer), e = normalized_answer(kind, expected);
  if (!a || !e) return false;
  if (kind == TaskKind::Pleochroism) {
    const auto g = colour_triple(a->get<std::string>()), x = colour_triple(e->get<std::string>());
    if (g.empty() || x.empty()) return false;
    for (int i = 0; i < 3; ++i)
      if (!colour_word_close(g[std::size_t(i)], x[std::size_t(i)])) return false;
    return true;
  }
  if (!task_kind_info(kind).numeric) return *a == *e;
  double x = a->get<double>(), y = e->get<double>();
  if (kind == TaskKind::ExtinctionAngle) {
    x = folded_extinction_angle_deg(x);
    y = folded_extinction_angle_deg(y);
  }
  // A tolerance is a closed interval; the 1e-9 keeps an answer typed as the key's rounded value
  // right when the tolerance is 0 (an interference order).
  return std::abs(x - y) <= tolerance.value_or(task_kind_info(kind).default_tolerance) + 1e-9;
}

}  // namespace pmsim
