#pragma once
// Scratch folders and hand-written map files for the EBSD reader tests: each test writes the
// bytes it reads, so what a reader is given is visible next to what it must make of it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/base/input_error.h"

namespace pmsim::ebsd_test {

namespace fs = std::filesystem;

class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("pmsim_ebsd_" + std::to_string(::getpid()) + "_" +
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

 private:
  fs::path path_;
};

// Every "\n" of `text` as "\r\n" (files written on Windows).
inline std::string crlf(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

// The InputError `f` throws (a test failure when it throws nothing or something else).
template <class F>
InputError input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-InputError: " << e.what();
    return InputError("", "", "", "");
  }
  ADD_FAILURE() << "threw nothing";
  return InputError("", "", "", "");
}

}  // namespace pmsim::ebsd_test
