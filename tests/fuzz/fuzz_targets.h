#pragma once
// Fuzz entry points: each takes the fuzzer's bytes, feeds them to one input path of pmsim, and
// aborts (fuzz::fail) when an oracle is violated: an exception other than InputError escaping a
// parser, a NaN/Inf in a result, energy not conserved, a valid scene that does not survive
// save → load. The same functions run under libFuzzer (fuzz_main.cpp, clang, PMSIM_FUZZ) and in
// the ordinary build's replay tests (replay_main.cpp). `*_seeds` write a seed corpus built from
// assets/ into a folder.
#include <cstddef>
#include <cstdint>
#include <string>

namespace pmsim::fuzz {

#define PMSIM_FUZZ_TARGETS(X) \
  X(scene_parser)             \
  X(scene_setting)            \
  X(lens_parser)              \
  X(material_parser)          \
  X(mineral_parser)           \
  X(trace_lens)               \
  X(plate_jones)

#define PMSIM_FUZZ_DECLARE(name)                        \
  int name(const std::uint8_t* data, std::size_t size); \
  void name##_seeds(const std::string& asset_dir, const std::string& out_dir);
PMSIM_FUZZ_TARGETS(PMSIM_FUZZ_DECLARE)
#undef PMSIM_FUZZ_DECLARE

}  // namespace pmsim::fuzz
