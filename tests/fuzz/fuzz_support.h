#pragma once
// Shared by the fuzz entry points (tests/fuzz/fuzz_*.cpp): a byte reader that turns fuzzer bytes
// into numbers in useful ranges (and now and then a raw, possibly absurd double, so that the
// validation layers see NaN, Inf and 1e300 too), its inverse for building seeds, a scratch file
// for parsers that read paths, and the oracle failure that libFuzzer records as a crash.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace pmsim::fuzz {

// An oracle violation: print what broke and abort, which libFuzzer keeps as a crash input and the
// replay test reports as a failure.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "pmsim fuzz oracle violated: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}
inline void check(bool ok, const std::string& what) {
  if (!ok) fail(what);
}

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}
  bool empty() const { return p_ >= end_; }
  std::uint8_t byte() { return p_ < end_ ? *p_++ : 0; }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(byte()) << (8 * i);
    return v;
  }
  double raw_double() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= std::uint64_t(byte()) << (8 * i);
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  // A tag byte, then either a value in [lo, hi] (tag < 0xF0) or a raw double (NaN, Inf, huge,
  // denormal...) 1 time in 16.
  double number(double lo, double hi) {
    const std::uint8_t tag = byte();
    if (tag >= 0xF0) return raw_double();
    return lo + (hi - lo) * (double(u32()) / 4294967295.0);
  }
  int integer(int lo, int hi) { return lo + int(u32() % std::uint32_t(hi - lo + 1)); }
  // Rest of the input as text.
  std::string rest() {
    std::string s(reinterpret_cast<const char*>(p_), reinterpret_cast<const char*>(end_));
    p_ = end_;
    return s;
  }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
};

// Builds inputs that ByteReader reads back as the given values (seed corpora).
class ByteWriter {
 public:
  void byte(std::uint8_t b) { out_.push_back(b); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) byte(std::uint8_t(v >> (8 * i)));
  }
  void number(double v, double lo, double hi) {
    byte(0);
    double f = (v - lo) / (hi - lo);
    f = f < 0 ? 0 : (f > 1 ? 1 : f);
    u32(std::uint32_t(std::llround(f * 4294967295.0)));
  }
  void integer(int v, int lo, int hi) { u32(std::uint32_t(v - lo) % std::uint32_t(hi - lo + 1)); }
  void text(const std::string& s) { out_.insert(out_.end(), s.begin(), s.end()); }
  const std::vector<std::uint8_t>& bytes() const { return out_; }

 private:
  std::vector<std::uint8_t> out_;
};

// A per-process scratch file for parsers that take a path (the real input path: open, read,
// parse, validate). PMSIM_FUZZ_SCRATCH names a folder private to one run (scripts/fuzz.sh): the
// path is then the same in every run, as a repeatable run needs (error messages quote it, and
// libFuzzer mutates with the values it sees compared); otherwise the pid keeps processes apart.
inline std::string write_scratch(const std::string& tag, const std::uint8_t* data, std::size_t size) {
  const char* own = std::getenv("PMSIM_FUZZ_SCRATCH");
  const char* dir = std::getenv("TMPDIR");
  const std::string path = own && *own ? std::string(own) + "/pmsim_fuzz_" + tag + ".json"
                                       : std::string(dir && *dir ? dir : "/tmp") + "/pmsim_fuzz_" +
                                             std::to_string(::getpid()) + "_" + tag + ".json";
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  f.close();
  if (!f) fail("cannot write the scratch file " + path);
  return path;
}

inline void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}
inline void write_file(const std::string& path, const std::string& text) {
  write_file(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

inline bool finite3(double a, double b, double c) {
  return std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
}

}  // namespace pmsim::fuzz
