#pragma once
// The app's file dialog: a modal ImGui window that walks the file system and offers the files a
// control can open (scene .json; thin-section .json and EBSD maps .ctf/.ang; exercises
// .pmexercise.json). Dear ImGui has no native dialog and the app must run under Xvfb and
// off-screen, so it is drawn like every other window. The path field has the keyboard focus:
// typing a path and Enter opens it, as a native dialog's location bar does.
#include <string>
#include <vector>

namespace pmsim::ui {

struct DirectoryEntry {
  std::string name;
  bool is_directory = false;
};

// The sub-folders of `dir` (names without a leading dot), then its files whose name ends with one
// of `extensions` (lower case with the dot, ".json" or ".pmexercise.json"; case-insensitive match),
// each group sorted by name.
// An unreadable folder gives an empty list and a message in `error`.
std::vector<DirectoryEntry> list_directory(const std::string& dir, const std::vector<std::string>& extensions,
                                           std::string& error);

class FileBrowser {
 public:
  // Opens the dialog on the next draw(), in the folder of `start` (a file or a folder; the current
  // folder when it names neither).
  void open(const std::string& title, const std::string& start, std::vector<std::string> extensions);
  bool is_open() const { return open_ || visible_; }
  // Draws the dialog while it is open. True on the frame a file was chosen, with its path in
  // `chosen`; the dialog then closes (Escape or Cancel close it without a choice).
  bool draw(std::string& chosen);

 private:
  void enter(const std::string& dir);

  std::string title_;
  std::vector<std::string> extensions_;
  std::string dir_;
  std::string path_field_;
  std::vector<DirectoryEntry> entries_;
  std::string error_;
  bool open_ = false;     // open() was called: OpenPopup on the next draw
  bool visible_ = false;  // the popup is showing
  bool focus_path_ = false;
};

}  // namespace pmsim::ui
