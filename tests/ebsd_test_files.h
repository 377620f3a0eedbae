#pragma once
// Scratch folders and hand-written map files for the EBSD reader tests: each test writes the
// bytes it reads, so what a reader is given is visible next to what it must make of it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/base/input_error.h"
#include "reliability_support.h"

namespace pmsim::ebsd_test {

namespace fs = std::filesystem;

// The reliability tests' scratch folder: a fresh folder per test, removed afterwards.
using ScratchDir = ::pmsim::reliability::ScratchDir;

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
