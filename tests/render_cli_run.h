#pragma once
// Runs pmsim-render as a new process, the way a user scripting it does, and keeps its exit code
// and standard error (the bad-input tests check both). Shared by the CLI tests.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pmsim::test {

inline const std::string kRenderBinary = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-render";

// A scratch folder per test process (named by `tag` and the pid, so parallel ctest runs differ).
inline std::string cli_temp_dir(const std::string& tag) {
  const auto d = std::filesystem::temp_directory_path() / ("pmsim_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d.string();
}

struct CliRun {
  int code;
  std::string err;
};

inline CliRun run_render_cli(const std::string& args, const std::string& scratch_dir) {
  const std::string err_file = scratch_dir + "/stderr.txt";
  const int status = std::system((kRenderBinary + " " + args + " 2>" + err_file + " >/dev/null").c_str());
  std::ifstream f(err_file);
  std::stringstream ss;
  ss << f.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

}  // namespace pmsim::test
