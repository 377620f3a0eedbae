#pragma once
// The one rule for names in the asset libraries (materials, minerals): names are looked up
// case-insensitively, and two files defining the same name are an error naming both files —
// silently keeping one would make the result depend on the order of files in the folder.
#include <map>
#include <string>

namespace pmsim {

class AssetNames {
 public:
  explicit AssetNames(std::string kind) : kind_(std::move(kind)) {}  // "medium", "mineral"
  // Records that `file` defines `name`; throws InputError(file, "name", name, "… already defined
  // in <the other file>") when another file defined it (in any letter case).
  void add(const std::string& name, const std::string& file);

 private:
  std::string kind_;
  std::map<std::string, std::string> file_of_;  // lower-case name → file that defined it
};

}  // namespace pmsim
