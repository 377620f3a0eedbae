#pragma once
// SplitMix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014):
// the project's one hash of a seed to 64 random bits, stateless so that a value depends on its
// inputs only (a pixel's sample, a grain's redrawn orientation), not on who draws it first.
#include <cstdint>

namespace pmsim {

constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Uniform in [0, 1) from 64 random bits: the top 53.
constexpr double unit_interval(std::uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

}  // namespace pmsim
