#include "ui/file_browser.h"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace pmsim::ui {
namespace fs = std::filesystem;

namespace {
std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
}  // namespace

std::vector<DirectoryEntry> list_directory(const std::string& dir, const std::vector<std::string>& extensions,
                                           std::string& error) {
  error.clear();
  std::vector<DirectoryEntry> folders, files;
  std::error_code ec;
  fs::directory_iterator it(dir, ec);
  if (ec) {
    error = dir + ": " + ec.message();
    return {};
  }
  for (const fs::directory_iterator end; it != end; it.increment(ec)) {
    if (ec) break;
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code type_ec;
    if (it->is_directory(type_ec)) {
      folders.push_back({name, true});
    } else if (it->is_regular_file(type_ec)) {
      // By the end of the name, so that a double extension (.pmexercise.json) can be asked for.
      const std::string lname = lower(name);
      const auto ends_with = [&](const std::string& ext) { return lname.size() > ext.size() && lname.ends_with(ext); };
      if (std::any_of(extensions.begin(), extensions.end(), ends_with)) files.push_back({name, false});
    }
  }
  if (ec) error = dir + ": " + ec.message();
  const auto by_name = [](const DirectoryEntry& a, const DirectoryEntry& b) { return a.name < b.name; };
  std::sort(folders.begin(), folders.end(), by_name);
  std::sort(files.begin(), files.end(), by_name);
  folders.insert(folders.end(), files.begin(), files.end());
  return folders;
}

void FileBrowser::open(const std::string& title, const std::string& start, std::vector<std::string> extensions) {
  title_ = title;
  extensions_ = std::move(extensions);
  std::error_code ec;
  fs::path p = start.empty() ? fs::current_path(ec) : fs::path(start);
  if (!fs::is_directory(p, ec)) p = p.parent_path();
  if (p.empty() || !fs::is_directory(p, ec)) p = fs::current_path(ec);
  enter(fs::absolute(p, ec).lexically_normal().string());
  open_ = true;
}

void FileBrowser::enter(const std::string& dir) {
  dir_ = dir;
  entries_ = list_directory(dir_, extensions_, error_);
  path_field_ = (fs::path(dir_) / "").string();
  focus_path_ = true;
}

bool FileBrowser::draw(std::string& chosen) {
  if (open_) {
    ImGui::OpenPopup(title_.c_str());
    open_ = false;
    visible_ = true;
  }
  if (!visible_) return false;
  bool picked = false;
  ImGui::SetNextWindowSize(ImVec2(560, 420), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(title_.c_str(), nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    visible_ = false;
    return false;
  }
  ImGui::TextUnformatted(dir_.c_str());
  if (ImGui::SmallButton("Up") && fs::path(dir_).has_parent_path() && fs::path(dir_).parent_path() != fs::path(dir_))
    enter(fs::path(dir_).parent_path().string());
  ImGui::SameLine();
  std::string shown;
  for (const auto& e : extensions_) shown += (shown.empty() ? "" : " ") + e;
  ImGui::TextDisabled("shows folders and %s", shown.c_str());
  if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());

  std::string go_to;
  ImGui::BeginChild("##entries", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2), true);
  for (const DirectoryEntry& e : entries_) {
    const std::string label = e.is_directory ? e.name + "/" : e.name;
    if (ImGui::Selectable(label.c_str(), false, ImGuiSelectableFlags_AllowDoubleClick)) {
      const std::string full = (fs::path(dir_) / e.name).string();
      if (e.is_directory)
        go_to = full;
      else
        path_field_ = full;
      if (!e.is_directory && ImGui::IsMouseDoubleClicked(0)) {
        chosen = full;
        picked = true;
      }
    }
  }
  ImGui::EndChild();
  if (!go_to.empty()) enter(go_to);

  char buffer[1024];
  std::strncpy(buffer, path_field_.c_str(), sizeof buffer - 1);
  buffer[sizeof buffer - 1] = '\0';
  ImGui::PushItemWidth(-170);
  if (focus_path_) {
    ImGui::SetKeyboardFocusHere();
    focus_path_ = false;
  }
  const bool entered = ImGui::InputText("##path", buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::PopItemWidth();
  path_field_ = buffer;
  ImGui::SameLine();
  const bool open_clicked = ImGui::Button("Open");
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
  if ((entered || open_clicked) && !picked && !path_field_.empty()) {
    // A relative path is relative to the folder shown, as in a location bar. (The field's text is
    // selected when it takes the focus, so typing replaces the folder written there.)
    fs::path typed(path_field_);
    if (typed.is_relative()) typed = fs::path(dir_) / typed;
    typed = typed.lexically_normal();
    std::error_code ec;
    if (fs::is_directory(typed, ec)) {
      enter(typed.string());
    } else {
      // A path that does not exist is still handed over: the control that opens it names the
      // file in its error, as for a path typed into its own field.
      chosen = typed.string();
      picked = true;
    }
  }
  if (picked || cancel) {
    visible_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  return picked;
}

}  // namespace pmsim::ui
