#include "core/bench/process_start.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace pmsim {

namespace {
// One spawn → exit; returns wall milliseconds, adds the child's peak RSS to rss_kb.
double run_once(const std::string& binary, const std::string& out, long& rss_kb) {
  std::vector<std::string> args = {binary,  "--set", "render.width=8", "--set", "render.height=8",
                                   "--out", out};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int err = posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) throw std::runtime_error("cannot start " + binary);
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("lost the child process of " + binary);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(binary + " failed on an 8x8 render (exit status " + std::to_string(status) +
                             ")");
  rss_kb = std::max(rss_kb, usage.ru_maxrss);
  return ms;
}
}  // namespace

ProcessStartResult measure_process_start(const std::string& render_binary, int runs) {
  const std::string out =
      (std::filesystem::temp_directory_path() / ("pmsim_bench_start_" + std::to_string(::getpid()) + ".png"))
          .string();
  ProcessStartResult r;
  long rss = 0;
  run_once(render_binary, out, rss);
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) ms.push_back(run_once(render_binary, out, rss));
  std::error_code ignored;
  std::filesystem::remove(out, ignored);
  std::sort(ms.begin(), ms.end());
  r.runs = runs;
  r.median_ms = ms.empty() ? 0.0 : (ms[(ms.size() - 1) / 2] + ms[ms.size() / 2]) / 2.0;
  r.min_ms = ms.empty() ? 0.0 : ms.front();
  r.max_ms = ms.empty() ? 0.0 : ms.back();
  r.max_rss_kb = rss;
  return r;
}

}  // namespace pmsim
