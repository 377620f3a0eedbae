#pragma once
// A folder under the system's temporary directory for the files a bench row writes and reads back
// (maps to load, scenes to render), named by the row and the process id so that concurrent runs do
// not meet, and removed with everything in it when the row is done or throws.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace pmsim {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag)
      : path_(std::filesystem::temp_directory_path() / ("pmsim-bench-" + tag + "-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace pmsim
