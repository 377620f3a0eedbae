// The Identify tab (issue 23, "every student can read the microscope"): the determinative aid of
// `pmsim-exercise identify` in the app. The student gives what they observed — words from combos,
// numbers and ranges typed — and reads the library minerals consistent with all of it, each with
// the reasons. A thin client: every observation goes through core's parse_observation and the
// matching is core's identify() (core/exercise/identify.h); the tab only keeps the text as typed.
#include <algorithm>
#include <cstring>
#include <set>

#include <imgui.h>

#include "core/base/input_error.h"
#include "core/exercise/mineral_signature.h"
#include "ui/app.h"

namespace pmsim::ui {
namespace {

// One observation: its key (as pmsim-exercise identify's --KEY), the label in the tab, and either
// the words of its combo (a choice) or a hint for its text field (a number or a range).
struct ObservationView {
  const char* key;
  const char* label;
  std::vector<std::string> words;  // empty: a text field
  const char* hint = "";
  const char* help = "";
};

// The twin laws any library mineral shows, for the twin combo ("any": a twin of unknown law).
std::vector<std::string> twin_words() {
  std::set<std::string> laws;
  for (const MineralSignature& s : library_signatures())
    for (const std::string& law : s.twin_laws) laws.insert(law);
  std::vector<std::string> words{"any"};
  words.insert(words.end(), laws.begin(), laws.end());
  return words;
}

const std::vector<ObservationView>& plane_light() {
  static const std::vector<ObservationView> v = {
      {"opaque", "Opaque", {"yes", "no"}, "", "black in plane and crossed light (magnetite, ilmenite)"},
      {"relief", "Relief", {"low", "moderate", "high", "very_high"}, "", "against the mount, n = 1.54"},
      {"relief-sign", "Relief sign", {"positive", "negative"}, "", "Becke line into (positive) or out of the grain"},
      {"n", "n (liquids)", {}, "1.55 or 1.54:1.56", "an index measured in immersion liquids, N or LOW:HIGH"},
      {"coloured", "Coloured", {"yes", "no"}, "", "in plane light"},
      {"pleochroic", "Pleochroic", {"yes", "no"}, "", "colour changes as the stage turns"},
      {"cleavages", "Cleavages", {}, "0-6", "cleavage directions seen in one grain"}};
  return v;
}

const std::vector<ObservationView>& crossed_polars() {
  static const std::vector<ObservationView> v = {
      {"order", "Highest order", {}, "0-20", "highest interference order seen (0: dark in every position)"},
      {"thickness", "Thickness um", {}, "30", "the section's thickness for the order (30 when empty)"},
      {"character", "Character", {"isotropic", "uniaxial", "biaxial"}, "", "from the interference figure"},
      {"sign", "Optic sign", {"positive", "negative"}, "", "from the figure with the gypsum plate"},
      {"two-v", "2V deg", {}, "40 or 30:50", "2V in degrees, N or LOW:HIGH"},
      {"extinction", "Extinction", {"parallel", "inclined", "symmetric"}, "", "to the elongation or cleavage"},
      {"extinction-angle", "Extinction deg", {}, "deg", "the largest extinction angle measured"},
      {"elongation", "Elongation", {"length-slow", "length-fast"}, "", "sign of elongation"},
      {"twin", "Twin", twin_words(), "", "a twin law seen, or any"}};
  return v;
}

}  // namespace

const std::vector<std::string>& identify_keys() {
  static const std::vector<std::string> keys = {"opaque", "relief", "relief-sign", "n", "coloured",
                                                "pleochroic", "order", "thickness", "character", "sign", "two-v",
                                                "extinction", "extinction-angle", "elongation", "cleavages",
                                                "twin"};
  return keys;
}

void App::update_identify() {
  if (!identify_.stale) return;
  // The observations as core parses them, one key at a time: a value core refuses (a half-typed
  // number) is left out and its reason shown beside its field.
  Observations o;
  identify_.errors.clear();
  for (const auto& [key, value] : identify_.values) {
    if (value.empty()) continue;
    try {
      o = parse_observation(o, key, value);
    } catch (const InputError& e) {
      identify_.errors[key] = e.reason;
    }
  }
  identify_.candidates = identify(o);
  identify_.stale = false;
}

bool App::identify_observation(const std::string& key, const std::string& value) {
  const auto& keys = identify_keys();
  if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
    fail(InputError("", "identify", key, "not an observation (opaque, relief, relief-sign, n, coloured, pleochroic, "
                                         "order, thickness, character, sign, two-v, extinction, extinction-angle, "
                                         "elongation, cleavages, twin)")
             .what());
    return false;
  }
  if (!value.empty()) {
    try {
      parse_observation(Observations{}, key, value);
    } catch (const InputError& e) {
      fail(e.what());
      return false;
    }
  }
  if (value.empty())
    identify_.values.erase(key);
  else
    identify_.values[key] = value;
  identify_.stale = true;
  identify_.select_tab = true;
  return true;
}

void App::identify_clear() {
  identify_.values.clear();
  identify_.stale = true;
  identify_.select_tab = true;
}

const std::vector<Candidate>& App::identify_candidates() {
  update_identify();
  return identify_.candidates;
}

void App::draw_identify_tab() {
  auto& values = identify_.values;
  const float field_w = ImGui::GetContentRegionAvail().x * 0.5f;
  auto row = [&](const ObservationView& v) {
    const std::string current = values.count(v.key) ? values.at(v.key) : std::string();
    ImGui::PushItemWidth(field_w);
    if (!v.words.empty()) {
      const char* preview = current.empty() ? "(not observed)" : current.c_str();
      if (ImGui::BeginCombo(v.label, preview)) {
        if (ImGui::Selectable("(not observed)", current.empty())) {
          values.erase(v.key);
          identify_.stale = true;
        }
        for (const std::string& w : v.words)
          if (ImGui::Selectable(w.c_str(), w == current)) {
            values[v.key] = w;
            identify_.stale = true;
          }
        ImGui::EndCombo();
      }
    } else {
      char buffer[64];
      std::strncpy(buffer, current.c_str(), sizeof buffer - 1);
      buffer[sizeof buffer - 1] = '\0';
      if (ImGui::InputTextWithHint(v.label, v.hint, buffer, sizeof buffer)) {
        std::string text = buffer;
        text.erase(0, text.find_first_not_of(' '));
        text.erase(text.find_last_not_of(' ') + 1);
        if (text.empty())
          values.erase(v.key);
        else
          values[v.key] = text;
        identify_.stale = true;
      }
    }
    ImGui::PopItemWidth();
    if (ImGui::IsItemHovered() && v.help[0]) ImGui::SetTooltip("%s", v.help);
    update_identify();
    if (const auto e = identify_.errors.find(v.key); e != identify_.errors.end())
      ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "  %s (left out)", e->second.c_str());
  };

  ImGui::TextWrapped("What you observed narrows the library's minerals; leave what you did not see.");
  ImGui::Separator();
  ImGui::TextUnformatted("Plane light");
  for (const auto& v : plane_light()) row(v);
  ImGui::Separator();
  ImGui::TextUnformatted("Crossed polars");
  for (const auto& v : crossed_polars()) row(v);
  if (ImGui::Button("Clear")) {
    values.clear();
    identify_.stale = true;
  }

  update_identify();
  const auto& found = identify_.candidates;
  ImGui::Separator();
  ImGui::TextUnformatted("Candidates");
  ImGui::Text("%zu of %zu library minerals fit", found.size(), library_signatures().size());
  if (found.empty()) ImGui::TextWrapped("None: check the observation you are least sure of.");
  for (const Candidate& c : found) {
    if (ImGui::TreeNode(c.mineral.c_str())) {
      if (c.why.empty()) ImGui::TextDisabled("(no observation given yet)");
      for (const std::string& w : c.why) ImGui::BulletText("%s", w.c_str());
      ImGui::TreePop();
    }
  }
}

}  // namespace pmsim::ui
