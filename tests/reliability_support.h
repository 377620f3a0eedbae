#pragma once
// Helpers shared by the reliability tests (tests/reliability_*_test.cpp): scratch folders, files
// with given bytes, running a command and capturing its exit code, stdout and stderr, and the
// InputError expectation every bad-input test makes.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>

#include "core/base/input_error.h"

namespace pmsim::reliability {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("pmsim_rel_" + std::to_string(::getpid()) + "_" +
             (info ? std::string(info->test_suite_name()) + "_" + info->name() : "x"));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name, const std::string& bytes) const {
    const fs::path p = path_ / name;
    std::ofstream f(p, std::ios::binary);
    f << bytes;
    return p.string();
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

inline std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Runs f and returns the InputError it threw; records a failure if it threw anything else or
// nothing (then returns nullopt).
inline std::optional<InputError> input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw an exception other than InputError: " << e.what();
    return std::nullopt;
  }
  ADD_FAILURE() << "bad input was accepted";
  return std::nullopt;
}

// True when the message's `shown` value is the `expected` one: literally, or as the same number
// reformatted (validation after parsing prints 1000000 as 1e+06 and 0.3 as 0.29999999999999999).
inline bool shows_value(const std::string& shown, const std::string& expected) {
  if (shown.find(expected) != std::string::npos) return true;
  char* end1 = nullptr;
  char* end2 = nullptr;
  const double a = std::strtod(shown.c_str(), &end1), b = std::strtod(expected.c_str(), &end2);
  if (shown.empty() || expected.empty() || *end1 != '\0' || *end2 != '\0') return false;
  return a == b || std::abs(a - b) <= 1e-15 * std::abs(b);
}

// The error must name the key and show the value (substring match: values are shown as the
// user wrote them, numbers may be reformatted).
#define EXPECT_INPUT_ERROR(expr, key_, value_)                                                     \
  do {                                                                                             \
    auto err_ = ::pmsim::reliability::input_error_of([&] { (void)(expr); });                       \
    if (err_) {                                                                                    \
      EXPECT_EQ(err_->key, std::string(key_)) << err_->what();                                     \
      EXPECT_TRUE(::pmsim::reliability::shows_value(err_->value, value_))                          \
          << "value '" << err_->value << "' does not show '" << (value_) << "': " << err_->what(); \
      EXPECT_NE(std::string(err_->what()).find(key_), std::string::npos) << err_->what();          \
    }                                                                                              \
  } while (0)

struct CommandResult {
  int exit_code = -1;  // 128 + signal when killed by one
  std::string out, err;
};

// Runs argv (no shell) with stdout and stderr captured through files in `scratch`.
inline CommandResult run_command(const std::vector<std::string>& argv, const ScratchDir& scratch,
                                 const std::vector<std::string>& env = {}) {
  const std::string out = scratch / ".stdout", err = scratch / ".stderr";
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::FILE* o = std::freopen(out.c_str(), "w", stdout);
    std::FILE* e = std::freopen(err.c_str(), "w", stderr);
    if (!o || !e) ::_exit(127);
    for (const std::string& kv : env) ::putenv(const_cast<char*>(kv.c_str()));
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_file(out);
  r.err = read_file(err);
  std::error_code ec;
  fs::remove(out, ec);
  fs::remove(err, ec);
  return r;
}

}  // namespace pmsim::reliability
